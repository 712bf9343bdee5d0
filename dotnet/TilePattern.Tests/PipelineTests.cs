// The whole pipeline through the public API: remesh -> match -> tiles -> report.
using System;
using System.Collections.Generic;
using System.Linq;
using NUnit.Framework;

namespace TilePattern.Tests
{
    [TestFixture]
    public class PipelineTests
    {
        static bool Adjacent(PolyMesh mesh, FacePair pair)
        {
            return mesh.Face(pair.A).Intersect(mesh.Face(pair.B)).Count() == 2;
        }

        static double Norm(double[] v)
        {
            return Math.Sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        }

        static double Dot(double[] a, double[] b)
        {
            return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        }

        [Test]
        public void CurvedShellFromTrianglesToReport()
        {
            PolyMesh surface = TestMeshes.CurvedTriangles(30, 1.5, 0.3);
            Assert.AreEqual(1800, surface.FaceCount);
            var tile = new TileOptions();
            var progress = new List<double>();
            PolyMesh quads = TilePatternEngine.Remesh(surface, RemeshOptions.ForTile(tile), new SyncProgress(progress.Add));
            Assert.AreEqual(0.0, progress[0], "remesh reports its start");
            Assert.AreEqual(1.0, progress[progress.Count - 1], "remesh reports its end");
            CollectionAssert.IsOrdered(progress, "remesh progress never goes back");
            Assert.That(quads.FaceCount, Is.InRange(60, 250), "about (1.5 / 0.145)^2 quads");
            Assert.IsTrue(quads.IsQuadMesh);
            TilePatternEngine.Validate(quads);

            var options = new PatternOptions { TimeLimitSeconds = 20 };
            using (Pattern pattern = TilePatternEngine.Match(quads, options))
            {
                Assert.AreEqual(quads.FaceCount, pattern.FaceCount);
                Assert.IsNotEmpty(pattern.Pairs);
                var used = new HashSet<int>();
                foreach (FacePair pair in pattern.Pairs)
                {
                    Assert.Less(pair.A, pair.B);
                    Assert.IsTrue(Adjacent(quads, pair), "pair " + pair + " shares an edge");
                    Assert.IsTrue(used.Add(pair.A) && used.Add(pair.B), "faces used once");
                }
                foreach (int f in pattern.Unpaired)
                    Assert.IsTrue(used.Add(f), "unpaired face " + f + " is in no pair");
                Assert.AreEqual(pattern.FaceCount, used.Count + pattern.ExcludedCount + pattern.NonQuadCount);
                Assert.That(pattern.Bound, Is.GreaterThanOrEqualTo(pattern.Objective - 1e-9));
                Assert.That(pattern.Gap, Is.InRange(0.0, 1.0));
                Assert.That(pattern.Seconds, Is.GreaterThanOrEqualTo(0.0));

                // Cut to the input surface, as `tilepattern run` does.
                Tiling tiling = TilePatternEngine.Tiles(pattern, tile, surface);
                Report report = tiling.Report;
                Assert.IsNotNull(report.Cutting);
                Assert.Greater(tiling.Tiles.Length, pattern.Pairs.Length / 2);
                Assert.AreEqual(quads.FaceCount, report.Faces);
                Assert.AreEqual(tiling.Tiles.Length - report.Cutting.FillerTiles, report.FullTiles + report.HalfTiles,
                    "full and half count the tiles on the quads by blank; filler pieces are counted apart");
                Assert.AreEqual(report.Cutting.FillerTiles, tiling.Tiles.Count(t => t.Faces.Length == 0));
                Assert.That(report.Cutting.TearPieces, Is.InRange(0, report.Cutting.FillerTiles));
                Assert.That(report.Cutting.TearCuts, Is.InRange(0, report.Cutting.TearPieces));
                Assert.That(report.Cutting.TearCuts + report.Cutting.TearHalves, Is.InRange(0, report.Cutting.TearPieces));
                Assert.IsNotNull(report.Pattern, "the report embeds the pattern");
                Assert.AreEqual(pattern.Pairs.Length, report.Pattern.Pairs);
                Assert.AreEqual(pattern.BoundSource, report.Pattern.BoundSource);
                Assert.AreEqual(report.Objective, report.Pattern.Objective);
                Assert.IsNotNull(report.Fit, "the fit runs by default");
                Assert.IsNotNull(report.Joints.BeforeFit);
                Assert.AreEqual(tiling.BoundaryCount, report.BoundaryTiles);
                Assert.AreEqual(tiling.BoundaryCount, report.Cutting.BoundaryTiles);
                Assert.That(report.Cutting.Coverage, Is.InRange(0.5, 1.0 + 1e-9));
                Assert.AreEqual(pattern.ContinuousJoints, report.ContinuousJoints);
                Assert.AreEqual(pattern.Objective, report.Objective, 1e-9);
                Assert.AreEqual(pattern.Status, report.Status);
                Assert.AreEqual(tile.Length, report.Tile.Length, 1e-12);
                Assert.AreEqual(tile.Joint, report.Tile.Joint, 1e-12);
                Assert.Greater(report.Joints.Contacts, 0);
                Assert.AreEqual(tile.Joint, report.Joints.Joint, 1e-12);
                Assert.That(report.Joints.MaxGap, Is.GreaterThanOrEqualTo(report.Joints.MinGap));
                Assert.IsNotNull(report.Sequence);
                Assert.Greater(report.Sequence.SupportTiles, 0);
                Assert.That(report.Sequence.ClimbingTiles, Is.InRange(0, report.Sequence.SlopedTiles));
                Assert.That(report.Sequence.SlopedTiles, Is.LessThanOrEqualTo(report.FullTiles));
                CollectionAssert.AreEquivalent(Enumerable.Range(0, tiling.Tiles.Length), tiling.Tiles.Select(t => t.Step), "steps number the tiles");
                Assert.AreEqual(tiling.Tiles.Length, tiling.CutList.Sum(g => g.Count), "the cut list counts every tile");
                CollectionAssert.AreEquivalent(tiling.CutList.Select(g => g.Label), tiling.Tiles.Select(t => t.Label).Distinct());
                StringAssert.Contains("\"full_tiles\"", report.Json);

                foreach (Tile t in tiling.Tiles)
                {
                    Assert.AreEqual(24, t.Corners.Length);
                    Assert.IsTrue(t.Corners.All(c => !double.IsNaN(c) && !double.IsInfinity(c)));
                    Assert.AreEqual(1.0, Norm(t.XAxis), 1e-9);
                    Assert.AreEqual(1.0, Norm(t.YAxis), 1e-9);
                    Assert.AreEqual(1.0, Norm(t.ZAxis), 1e-9);
                    Assert.AreEqual(0.0, Dot(t.XAxis, t.YAxis), 1e-9);
                    Assert.AreEqual(0.0, Dot(t.XAxis, t.ZAxis), 1e-9);
                    // Right-handed: z = x cross y (a Rhino Plane(origin, x, y) has the tile's z).
                    double[] x = t.XAxis, y = t.YAxis;
                    Assert.AreEqual(1.0, Dot(new[] { x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0] }, t.ZAxis), 1e-9);
                    if (t.Kind == TileKind.Full && t.Faces.Length > 0)
                    {
                        Assert.AreEqual(2, t.Faces.Length);
                        Assert.AreEqual(tile.Length, t.Length, 1e-12);
                        Assert.AreEqual(tile.Width, t.Width, 1e-12);
                    }
                    else if (t.Kind == TileKind.Half)
                    {
                        Assert.LessOrEqual(t.Faces.Length, 1);
                        Assert.AreEqual(tile.Length / 2, t.Length, 1e-12);
                    }
                    if (t.Kind == TileKind.Boundary || t.Kind == TileKind.FitCut)
                    {
                        Assert.IsNotEmpty(t.Outline);
                        Assert.That(t.KeptFraction, Is.GreaterThan(0.0).And.LessThan(1.0));
                        StringAssert.StartsWith(t.Kind == TileKind.Boundary ? "B" : "C", t.Label);
                    }
                    else
                    {
                        Assert.IsEmpty(t.Outline);
                        Assert.AreEqual(1.0, t.KeptFraction);
                        Assert.AreEqual(t.Kind == TileKind.Full ? "F" : "H", t.Label);
                    }
                    Assert.AreEqual(tile.Thickness, t.Thickness, 1e-12);
                    // Corner 4 is corner 0 moved by the thickness along z.
                    double[] c0 = t.Corner(0), c4 = t.Corner(4);
                    Assert.AreEqual(t.Thickness, Norm(new[] { c4[0] - c0[0], c4[1] - c0[1], c4[2] - c0[2] }), 1e-9);
                }
            }
        }

        [Test]
        public void AGapStopsTheSearchOnceCloseEnough()
        {
            // The paper's plain program on CBC would prove 10 x 10 (w = 0.5) only by branching;
            // with a 5 % gap it stops at the first pattern that close to its bound.
            Assert.AreEqual(0.0, new PatternOptions().Gap);
            var options = new PatternOptions { Method = SolveMethod.Mip, Formulation = Formulation.Paper, TimeLimitSeconds = 60, Gap = 0.05 };
            using (Pattern pattern = TilePatternEngine.Match(TestMeshes.Grid(10, 10), options))
            {
                Assert.AreEqual(SolveStatus.Feasible, pattern.Status);
                Assert.That(pattern.Gap, Is.GreaterThan(0.0).And.LessThanOrEqualTo(0.05));
            }
        }

        [Test]
        public void AClosedSurfaceIsReportedThroughWarnings()
        {
            // Faces of side 2: the C tests' 1.9 x 0.95 tile fits them.
            PolyMesh cube = TestMeshes.Cube(2);
            var tile = new TileOptions { Length = 3.9, Width = 1.9, Thickness = 0.1, Joint = 0.1 };
            using (Pattern pattern = TilePatternEngine.Match(cube, new PatternOptions { TimeLimitSeconds = 5 }))
            {
                Tiling tiling = TilePatternEngine.Tiles(pattern, tile);
                var codes = tiling.Report.Warnings.Select(w => w.Code).ToList();
                CollectionAssert.Contains(codes, TilingWarningCode.ClosedSurface);
                CollectionAssert.Contains(codes, TilingWarningCode.NoSupport);
                Assert.AreEqual("no_boundary", tiling.Report.Sequence.Support);
                Assert.AreEqual(0, tiling.Report.Sequence.SupportTiles);
                foreach (TilingWarning w in tiling.Report.Warnings)
                {
                    Assert.That(w.Message.Length, Is.GreaterThan(30), w.Name);
                    StringAssert.Contains(w.Name, tiling.Report.Json, "the same codes as report.json");
                }
            }
            // A plain grid stood up as a wall on its bottom edge: no warning.
            PolyMesh wall = TestMeshes.Grid(10, 10);
            using (Pattern pattern = TilePatternEngine.Match(wall, new PatternOptions { TimeLimitSeconds = 5 }))
            {
                var tile2 = new TileOptions { Length = 1.9, Width = 0.95, Thickness = 0.1, Joint = 0.1, Up = new[] { 0.0, 1.0, 0.0 } };
                Assert.AreEqual(0, TilePatternEngine.Tiles(pattern, tile2).Report.Warnings.Length);
            }
        }

        [Test]
        public void HerringboneAndBasketWeaveOnAnEightByEightGrid()
        {
            // Issue 20: the basket weave of an 8 x 8 grid is 16 squares of two parallel tiles,
            // alternating: every face paired, no pair penalised, proven.
            PolyMesh grid = TestMeshes.Grid(8, 8);
            using (Pattern pattern = TilePatternEngine.Match(grid, new PatternOptions { Bond = Bond.BasketWeave, Courses = Courses.Free }))
            {
                Assert.AreEqual(32, pattern.Pairs.Length);
                Assert.AreEqual(SolveStatus.Optimal, pattern.Status);
                Assert.AreEqual(32.0, pattern.Objective);
                // Each tile within one 2 x 2 square: its first face at even x (along x) or even y.
                Assert.IsTrue(pattern.Pairs.All(p => p.B == p.A + 1 ? p.A % 2 == 0 : (p.A / 8) % 2 == 0));
            }
            using (Pattern pattern = TilePatternEngine.Match(grid, new PatternOptions { Bond = Bond.Herringbone, Courses = Courses.Free, TimeLimitSeconds = 5 }))
            {
                Assert.Greater(pattern.Pairs.Length, 0);
                Assert.GreaterOrEqual(pattern.Bound, pattern.Objective);
            }
            var level = Assert.Throws<InvalidArgumentException>(() =>
                TilePatternEngine.Match(grid, new PatternOptions { Bond = Bond.Herringbone, Courses = Courses.Level }));
            StringAssert.Contains("courses free", level.Message);
        }

        [Test]
        public void PaperFigure5OnATenByTenGrid()
        {
            // The C tests' case: 49 tiles, no continuous joint, proven optimal.
            PolyMesh grid = TestMeshes.Grid(10, 10);
            using (Pattern pattern = TilePatternEngine.Match(grid, new PatternOptions { Weight = 2.0 }))
            {
                Assert.AreEqual(49, pattern.Pairs.Length);
                Assert.AreEqual(2, pattern.Unpaired.Length);
                Assert.AreEqual(0, pattern.ContinuousJoints);
                Assert.AreEqual(SolveStatus.Optimal, pattern.Status);
                Assert.AreEqual(BoundSource.LinearRelaxation, pattern.BoundSource, "no matching proves 49 < 50; the star rows' linear relaxation does");
                Assert.AreEqual(49.0, pattern.Objective);
                Assert.AreEqual(49.0, pattern.Bound);
                Assert.IsTrue(pattern.Pairs.All(p => (p.B == p.A + 1 && p.A % 10 != 9) || p.B == p.A + 10));
                using (Pattern paper = TilePatternEngine.Match(grid, new PatternOptions { Weight = 2.0, Method = SolveMethod.Mip }))
                {
                    Assert.AreEqual(BoundSource.WholeProgram, paper.BoundSource, "the paper's route proves it by branch and bound");
                    Assert.AreEqual(49.0, paper.Objective);
                }

                // Placed as in the paper (section 3.5): no fit.
                var tile = new TileOptions { Length = 1.9, Width = 0.95, Thickness = 0.1, Joint = 0.1, Fit = false };
                Tiling tiling = TilePatternEngine.Tiles(pattern, tile);
                Assert.IsNull(tiling.Report.Fit);
                Assert.AreEqual(51, tiling.Tiles.Length);
                Assert.AreEqual(TileKind.Full, tiling.Tiles[0].Kind);
                Assert.AreEqual(TileKind.Half, tiling.Tiles[50].Kind);
                Assert.AreEqual(1.9, tiling.Tiles[0].Length);
                Assert.AreEqual(0.95, tiling.Tiles[50].Length);
                Assert.AreEqual(1.0, tiling.Tiles[0].ZAxis[2], 1e-12);
                Assert.AreEqual(0.0, tiling.Tiles[0].Corners[2]);
                Assert.AreEqual(0.1, tiling.Tiles[0].Corners[4 * 3 + 2], 1e-12);
                Assert.AreEqual(49, tiling.Report.FullTiles);
                Assert.AreEqual(SolveStatus.Optimal, tiling.Report.Status);
                Assert.AreEqual("optimal", tiling.Report.StatusText);
                for (int i = 0; i < tiling.Tiles.Length; i++)
                    Assert.AreEqual(i, tiling.Tiles[i].Index);
            }
        }

        [Test]
        public void BoundaryTilesAreCutToTheSurface()
        {
            // The C tests' case: quads reach x = 10, the surface ends at x = 6.5; the paper's
            // placement (no fit).
            PolyMesh grid = TestMeshes.Grid(10, 10);
            PolyMesh surface = TestMeshes.Grid(13, 20, 0.5);
            var tile = new TileOptions { Length = 1.9, Width = 0.95, Thickness = 0.1, Joint = 0.1, Fit = false };
            using (Pattern pattern = TilePatternEngine.Match(grid, new PatternOptions { Weight = 2.0 }))
            {
                Tiling cut = TilePatternEngine.Tiles(pattern, tile, surface);
                Assert.That(cut.Tiles.Length, Is.InRange(21, 50));
                Assert.Greater(cut.BoundaryCount, 0);
                foreach (Tile t in cut.Tiles)
                {
                    Assert.AreEqual(t.Kind == TileKind.Boundary, t.KeptFraction < 1.0, "tile " + t.Index);
                    for (int l = 0; l < t.Outline.Length; l++)
                    {
                        Assert.GreaterOrEqual(t.Outline[l].Length, 6, "a loop has 3 points or more");
                        double[] xyz = t.OutlineInModel(l);
                        for (int p = 0; p < xyz.Length; p += 3)
                        {
                            Assert.LessOrEqual(xyz[p], 6.5 + 1e-6, "kept outline stays on the surface");
                            Assert.AreEqual(0.0, xyz[p + 2], 1e-9);
                        }
                    }
                }
                CollectionAssert.Contains(cut.Tiles.Select(t => t.Label).ToList(), "B1");
                CutGroup b1 = cut.CutList.Single(g => g.Label == "B1");
                Assert.AreEqual("boundary", b1.Kind);
                Assert.Greater(b1.Count, 0);
                Assert.AreEqual(1.9, Math.Max(b1.BlankLength, 0.95), 1e-12);
                StringAssert.Contains("\"label\": \"B1\"", cut.CutListJson);
                Assert.AreEqual(cut.Tiles.Length, cut.CutList.Sum(g => g.Count));

                // Without a surface, the quad mesh's own boundary: nothing to cut on a grid.
                Tiling whole = TilePatternEngine.Tiles(pattern, tile);
                Assert.AreEqual(51, whole.Tiles.Length);
                Assert.AreEqual(0, whole.BoundaryCount);
            }
        }

        [Test]
        public void ForcedPairsAndExcludedFacesAreHonoured()
        {
            PolyMesh grid = TestMeshes.Grid(10, 10);
            var options = new PatternOptions();
            options.ForcedPairs.Add(new FacePair(0, 10));
            options.ExcludedFaces.Add(99);
            using (Pattern pattern = TilePatternEngine.Match(grid, options))
            {
                Assert.AreEqual(1, pattern.ExcludedCount);
                CollectionAssert.Contains(pattern.Pairs, new FacePair(0, 10));
                Assert.IsFalse(pattern.Pairs.Any(p => p.A == 99 || p.B == 99));
                CollectionAssert.DoesNotContain(pattern.Unpaired, 99);
            }
        }

        [Test]
        public void StackBondIsAMaximumMatching()
        {
            using (Pattern pattern = TilePatternEngine.Match(TestMeshes.Grid(10, 10), new PatternOptions { Bond = Bond.Stack }))
            {
                Assert.AreEqual(50, pattern.Pairs.Length);
                Assert.IsEmpty(pattern.Unpaired);
            }
        }

        [Test]
        public void TilesOnAnEqualCopyOfTheMeshMatchTilesOnTheSolvedMesh()
        {
            PolyMesh grid = TestMeshes.Grid(6, 4);
            using (Pattern pattern = TilePatternEngine.Match(grid))
            {
                var tile = new TileOptions { Length = 1.9, Width = 0.95, Thickness = 0.1, Joint = 0.1 };
                Tiling a = TilePatternEngine.Tiles(pattern, tile);
                Tiling b = TilePatternEngine.Tiles(TestMeshes.Grid(6, 4), pattern, tile);
                Assert.AreEqual(a.Tiles.Length, b.Tiles.Length);
                for (int i = 0; i < a.Tiles.Length; i++)
                    CollectionAssert.AreEqual(a.Tiles[i].Corners, b.Tiles[i].Corners);
            }
        }

        [Test]
        public void RemeshOptionsReachTheLibrary()
        {
            PolyMesh surface = TestMeshes.CurvedTriangles(24, 1.2, 0.2);
            PolyMesh coarse = TilePatternEngine.Remesh(surface, new RemeshOptions { TargetEdge = 0.3 });
            PolyMesh fine = TilePatternEngine.Remesh(surface, new RemeshOptions { TargetEdge = 0.15, Direction = FieldDirection.Angle, AngleDegrees = 45 });
            PolyMesh along = TilePatternEngine.Remesh(surface, new RemeshOptions { TargetEdge = 0.15, Direction = FieldDirection.Vector, DirectionVector = new[] { 1.0, 1.0, 0.0 }, ShapeUp = true });
            PolyMesh smooth = TilePatternEngine.Remesh(surface, new RemeshOptions { TargetEdge = 0.15, Direction = FieldDirection.Smooth });
            Assert.Less(coarse.FaceCount, fine.FaceCount);
            Assert.Greater(along.FaceCount, coarse.FaceCount);
            Assert.Greater(smooth.FaceCount, coarse.FaceCount);
        }

        /// <summary>Quads with corners on both sides of the fold at x = 1.2.</summary>
        static int QuadsOverTheFold(PolyMesh quads)
        {
            int over = 0;
            for (int f = 0; f < quads.FaceCount; f++)
            {
                bool left = false, right = false;
                foreach (int v in quads.Face(f))
                {
                    double x = quads.Vertex(v)[0] - 1.2;
                    left |= x < -0.01;
                    right |= x > 0.01;
                }
                if (left && right)
                    over++;
            }
            return over;
        }

        [Test]
        public void CreasesSplitAFoldedPlateUnlessTurnedOff()
        {
            // 2.4 x 1.2 m, folded along x = 1.2: the halves turn by 44 degrees.
            PolyMesh plate = TestMeshes.Grid(24, 12, 0.1, (x, y) => 0.4 * Math.Abs(x - 1.2));
            PolyMesh split = TilePatternEngine.Remesh(plate, new RemeshOptions());
            PolyMesh joined = TilePatternEngine.Remesh(plate, new RemeshOptions { Creases = false });
            Assert.AreEqual(0, QuadsOverTheFold(split));
            Assert.Greater(QuadsOverTheFold(joined), 0);
            using (Pattern pattern = TilePatternEngine.Match(split, new PatternOptions { TimeLimitSeconds = 5 }))
            {
                int cut = TilePatternEngine.Tiles(pattern, new TileOptions(), plate).Tiles.Count(t => t.Kind == TileKind.Boundary);
                int uncut = TilePatternEngine.Tiles(pattern, new TileOptions { Creases = false }, plate).Tiles.Count(t => t.Kind == TileKind.Boundary);
                Assert.Greater(cut, uncut, "tiles cut to the fold");
            }
        }

        [Test]
        public void OptionsStartFromTheLibraryDefaults()
        {
            var p = new PatternOptions();
            Assert.AreEqual(Bond.Staggered, p.Bond);
            Assert.AreEqual(0.5, p.Weight);
            Assert.AreEqual(60.0, p.TimeLimitSeconds);
            Assert.AreEqual(SolveMethod.Auto, p.Method);
            Assert.AreEqual(Formulation.Strengthened, p.Formulation);
            var r = new RemeshOptions();
            Assert.AreEqual(0.145, r.TargetEdge);
            Assert.AreEqual(FieldDirection.Curvature, r.Direction);
            Assert.IsFalse(r.ShapeUp);
            var t = new TileOptions();
            Assert.AreEqual(0.28, t.Length);
            Assert.AreEqual(0.14, t.Width);
            Assert.AreEqual(0.015, t.Thickness);
            Assert.AreEqual(0.01, t.Joint);
            Assert.Less(t.CutTolerance, 0.0, "negative: automatic");
            Assert.Less(t.MinKeptWidth, 0.0);
            Assert.Less(t.SupportBand, 0.0);
            CollectionAssert.AreEqual(new[] { 0.0, 0.0, 1.0 }, t.Up);
            Assert.AreEqual(0.145, RemeshOptions.ForTile(t).TargetEdge, 1e-15);
            // ABI 3: courses and the fit.
            Assert.AreEqual(Courses.Free, p.Courses);
            CollectionAssert.AreEqual(new[] { 0.0, 0.0, 1.0 }, p.Up);
            Assert.IsTrue(t.Fit);
            Assert.AreEqual(10.0, t.FitTimeLimitSeconds);
            Assert.Less(t.OverlapTolerance, 0.0, "negative: a twentieth of the joint");
            Assert.Less(t.BondTolerance, 0.0, "negative: a tenth of the length");
            Assert.AreEqual(0.001, t.UnitsPerMm, "a model in metres");
            Assert.AreEqual(0.145, RemeshOptions.ForTile(t, Courses.Free).TargetEdge, 1e-15);
            Assert.AreEqual(0.15, RemeshOptions.ForTile(t, Courses.Level).TargetEdge, 1e-15, "a course's height: width + joint");
            // ABI 7: split at the creases.
            Assert.IsTrue(r.Creases);
            Assert.IsTrue(t.Creases);
            // ABI 8: the field's renormalisation strength.
            Assert.AreEqual(0.5, r.Renormalisation);
        }

        [Test]
        public void RenormalisationPlacesTheConesOfARoundDomeElsewhere()
        {
            PolyMesh dome = TestMeshes.RoundDome();
            PolyMesh half = TilePatternEngine.Remesh(dome, new RemeshOptions());
            PolyMesh again = TilePatternEngine.Remesh(dome, new RemeshOptions { Renormalisation = 0.5 });
            PolyMesh twice = TilePatternEngine.Remesh(dome, new RemeshOptions { Renormalisation = 1.0 });
            CollectionAssert.AreEqual(half.Vertices, again.Vertices);
            CollectionAssert.AreNotEqual(half.Vertices, twice.Vertices);
            var e = Assert.Throws<InvalidArgumentException>(() => TilePatternEngine.Remesh(dome, new RemeshOptions { Renormalisation = -1.0 }));
            StringAssert.Contains("renormalisation", e.Message);
        }

        [Test]
        public void VersionAndAbi()
        {
            Assert.AreEqual(TilePatternEngine.AbiVersion, TilePatternEngine.NativeAbiVersion);
            StringAssert.IsMatch(@"^\d+\.\d+\.\d+", TilePatternEngine.NativeVersion);
        }

        [Test]
        public void PolyMeshRoundTrip()
        {
            var mesh = PolyMesh.FromFaces(new double[] { 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 2, 0, 0 }, new[] { new[] { 0, 1, 2, 3 }, new[] { 1, 4, 2 } });
            Assert.AreEqual(5, mesh.VertexCount);
            Assert.AreEqual(2, mesh.FaceCount);
            CollectionAssert.AreEqual(new[] { 4, 3 }, mesh.FaceSizes);
            CollectionAssert.AreEqual(new[] { 1, 4, 2 }, mesh.Face(1));
            CollectionAssert.AreEqual(new[] { 1.0, 1.0, 0.0 }, mesh.Vertex(2));
            Assert.IsFalse(mesh.IsQuadMesh);
            CollectionAssert.AreEqual(new[] { 0.5, 0.5, 0.0 }, mesh.FaceCenter(0));
            TilePatternEngine.Validate(mesh);
            // The arrays handed out are copies.
            mesh.Vertices[0] = 42;
            Assert.AreEqual(0.0, mesh.Vertex(0)[0]);
        }
    }

    /// <summary>An IProgress that reports synchronously (System.Progress posts to a thread pool).</summary>
    internal sealed class SyncProgress : IProgress<double>
    {
        readonly Action<double> report;

        public SyncProgress(Action<double> report)
        {
            this.report = report;
        }

        public void Report(double value)
        {
            report(value);
        }
    }
}

// The fit stage (stage 3b) and level courses through the wrapper: options, the report's fit
// figures, joint deviations, progress and cancellation of the fit, ABI 2 sized structs.
using System;
using System.Collections.Generic;
using System.Linq;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
using System.Threading;
using NUnit.Framework;

namespace TilePattern.Tests
{
    [TestFixture]
    public class FitTests
    {
        static PolyMesh surface, quads, wave, waveQuads;

        // A doubly curved shell, remeshed once for the fixture.
        static PolyMesh Surface { get { return surface ?? (surface = TestMeshes.CurvedTriangles(30, 1.5, 0.3)); } }

        static PolyMesh Quads { get { return quads ?? (quads = TilePatternEngine.Remesh(Surface, RemeshOptions.ForTile(new TileOptions()))); } }

        static PolyMesh Wave { get { return wave ?? (wave = TestMeshes.Wave()); } }

        static PolyMesh WaveQuads { get { return waveQuads ?? (waveQuads = TilePatternEngine.Remesh(Wave, RemeshOptions.ForTile(new TileOptions()))); } }

        static Pattern Solve(PolyMesh mesh, PatternOptions options = null)
        {
            return TilePatternEngine.Match(mesh, options ?? new PatternOptions { TimeLimitSeconds = 5 });
        }

        static readonly FitStatus[] Finished = { FitStatus.Converged, FitStatus.IterationLimit, FitStatus.TimeLimit };

        [Test]
        public void TheFitRunsByDefaultAndReportsItsFigures()
        {
            using (Pattern pattern = Solve(Quads))
            {
                Tiling tiling = TilePatternEngine.Tiles(pattern, new TileOptions(), Surface);
                Report report = tiling.Report;
                FitReport fit = report.Fit;
                Assert.IsNotNull(fit);
                CollectionAssert.Contains(Finished, fit.Status, fit.StatusText);
                Assert.GreaterOrEqual(fit.Iterations, 1);
                Assert.LessOrEqual(fit.ObjectiveAfter, fit.ObjectiveBefore);
                Assert.That(fit.MeanMove, Is.InRange(0.0, fit.MaxMove));
                Assert.GreaterOrEqual(report.FitSeconds, 0.0);
                Assert.LessOrEqual(report.FitSeconds, report.TileSeconds);

                JointReport after = report.Joints, before = after.BeforeFit;
                Assert.IsNotNull(before);
                Assert.IsNull(before.BeforeFit);
                Assert.Greater(before.Contacts, 0);
                Assert.AreEqual(after.Joint, before.Joint);
                Assert.Less(after.P95Deviation, before.P95Deviation, "the fit brings the joints closer to the nominal joint");
                Assert.That(after.Within2Mm, Is.InRange(before.Within2Mm, 1.0));
                Assert.That(after.Within2Mm, Is.LessThanOrEqualTo(after.Within5Mm));
                Assert.GreaterOrEqual(after.FitCuts, tiling.FitCutCount);
                StringAssert.Contains("\"before_fit\"", report.Json);
            }
        }

        [Test]
        public void FitOffKeepsThePapersPlacement()
        {
            using (Pattern pattern = Solve(Quads))
            {
                Tiling paper = TilePatternEngine.Tiles(pattern, new TileOptions { Fit = false }, Surface);
                Assert.IsNull(paper.Report.Fit);
                Assert.IsNull(paper.Report.Joints.BeforeFit);
                Assert.AreEqual(0.0, paper.Report.FitSeconds);
                Assert.AreEqual(0, paper.FitCutCount);
                Assert.AreEqual(0, paper.Report.Joints.FitCuts);
                // The fitted tiles started from this placement.
                Tiling fitted = TilePatternEngine.Tiles(pattern, new TileOptions(), Surface);
                Assert.AreEqual(paper.Report.Joints.MinGap, fitted.Report.Joints.BeforeFit.MinGap, 0.02);
                Assert.AreNotEqual(paper.Tiles[0].Origin, fitted.Tiles[0].Origin);
            }
        }

        [Test]
        public void EveryTileHasItsWorstJoint()
        {
            using (Pattern pattern = Solve(Quads))
                foreach (bool fit in new[] { true, false })
                {
                    Tiling tiling = TilePatternEngine.Tiles(pattern, new TileOptions { Fit = fit }, Surface);
                    Assert.IsTrue(tiling.Tiles.All(t => t.JointDeviation >= 0.0 && !double.IsInfinity(t.JointDeviation)));
                    JointReport j = tiling.Report.Joints;
                    double worst = Math.Max(Math.Abs(j.MinGap - j.Joint), Math.Abs(j.MaxGap - j.Joint));
                    Assert.AreEqual(worst, tiling.Tiles.Max(t => t.JointDeviation), 1e-15, "fit " + fit);

                    // Parallel to the tiles in the host's lists.
                    TileOutputs<string> outputs = TileOutputs<string>.Build(tiling, (t, pieces) => t.Label);
                    Assert.AreEqual(tiling.Tiles.Length, outputs.Deviations.Count);
                    for (int i = 0; i < tiling.Tiles.Length; i++)
                        Assert.AreEqual(tiling.Tiles[i].JointDeviation, outputs.Deviations[i]);
                }
        }

        [Test]
        public void FitOptionsReachTheLibrary()
        {
            using (Pattern pattern = Solve(Quads))
            {
                // A model in metres read as millimetres: every joint is within "2 mm".
                Tiling metres = TilePatternEngine.Tiles(pattern, new TileOptions(), Surface);
                Tiling asMm = TilePatternEngine.Tiles(pattern, new TileOptions { UnitsPerMm = 1.0 }, Surface);
                Assert.Less(metres.Report.Joints.Within2Mm, 1.0);
                Assert.AreEqual(1.0, asMm.Report.Joints.Within2Mm);
                // No time: the placement after the first step, with an honest status.
                Tiling hurried = TilePatternEngine.Tiles(pattern, new TileOptions { FitTimeLimitSeconds = 0 }, Surface);
                Assert.AreEqual(FitStatus.TimeLimit, hurried.Report.Fit.Status);
                Assert.AreEqual("time_limit", hurried.Report.Fit.StatusText);
                // A loose overlap tolerance is what the fit leaves at most.
                Tiling loose = TilePatternEngine.Tiles(pattern, new TileOptions { OverlapTolerance = 0.05, BondTolerance = 0.0 }, Surface);
                Assert.LessOrEqual(loose.Report.Joints.MaxOverlap, 0.05 + 1e-12);
            }
        }

        [Test]
        public void BadFitOptionsAreRefused()
        {
            using (Pattern pattern = Solve(TestMeshes.Grid(6, 4, 0.145)))
            {
                var cases = new[]
                {
                    new KeyValuePair<TileOptions, string>(new TileOptions { FitTimeLimitSeconds = double.NaN }, "fit_time_limit_seconds NaN"),
                    new KeyValuePair<TileOptions, string>(new TileOptions { FitTimeLimitSeconds = -1 }, "fit_time_limit_seconds -1"),
                    new KeyValuePair<TileOptions, string>(new TileOptions { OverlapTolerance = double.PositiveInfinity }, "overlap_tolerance"),
                    new KeyValuePair<TileOptions, string>(new TileOptions { BondTolerance = double.NaN }, "bond_tolerance"),
                    new KeyValuePair<TileOptions, string>(new TileOptions { UnitsPerMm = 0 }, "must be"),
                };
                foreach (var c in cases)
                {
                    var e = Assert.Throws<InvalidArgumentException>(() => TilePatternEngine.Tiles(pattern, c.Key), c.Value);
                    Assert.AreEqual(TilePatternStatus.InvalidArgument, e.Status);
                    StringAssert.Contains(c.Value, e.NativeMessage);
                }
                // With the fit off its options are not read.
                Assert.IsNotNull(TilePatternEngine.Tiles(pattern, new TileOptions { Fit = false, FitTimeLimitSeconds = double.NaN }));
            }
        }

        [Test]
        public void LevelCoursesOnASlopedGridRunOneWay()
        {
            // Rising along y: level courses run along x, so every tile pairs face f with f + 1.
            PolyMesh sloped = TestMeshes.Grid(8, 6, 1.0, (x, y) => 0.3 * y);
            using (Pattern free = Solve(sloped))
                Assert.IsTrue(free.Pairs.Any(p => p.B != p.A + 1), "free tiles lie both ways");
            using (Pattern level = Solve(sloped, new PatternOptions { TimeLimitSeconds = 5, Courses = Courses.Level }))
            {
                Assert.IsNotEmpty(level.Pairs);
                Assert.IsTrue(level.Pairs.All(p => p.B == p.A + 1 && p.A % 8 != 7), string.Join(" ", level.Pairs.Select(p => p.ToString()).ToArray()));
                Tiling tiling = TilePatternEngine.Tiles(level, new TileOptions { Length = 1.9, Width = 0.95, Thickness = 0.1, Joint = 0.1 });
                Assert.IsNotNull(tiling.Report.Fit);
            }
            // Up along x: courses along y, tiles pair f with f + 8.
            using (Pattern across = Solve(sloped, new PatternOptions { TimeLimitSeconds = 5, Courses = Courses.Level, Up = new[] { 1.0, 0.0, 0.0 } }))
            {
                Assert.IsNotEmpty(across.Pairs);
                Assert.IsTrue(across.Pairs.All(p => p.B == p.A + 8));
            }
        }

        [Test]
        public void BadCoursesAreRefused()
        {
            PolyMesh grid = TestMeshes.Grid(4, 4);
            var e = Assert.Throws<InvalidArgumentException>(() => TilePatternEngine.Match(grid, new PatternOptions { Courses = (Courses)7 }));
            StringAssert.Contains("courses 7", e.NativeMessage);
            e = Assert.Throws<InvalidArgumentException>(() => TilePatternEngine.Match(grid, new PatternOptions { Courses = Courses.Level, Up = new[] { 0.0, 0.0, 0.0 } }));
            StringAssert.Contains("up direction", e.NativeMessage);
            Assert.Throws<ArgumentException>(() => TilePatternEngine.Match(grid, new PatternOptions { Up = new[] { 0.0, 1.0 } }));
        }

        [Test]
        public void ProgressOfTheFitIsReportedOnTheCallingThread()
        {
            using (Pattern pattern = Solve(Quads))
            {
                var seen = new List<double>();
                int thread = Thread.CurrentThread.ManagedThreadId;
                TilePatternEngine.Tiles(pattern, new TileOptions(), Surface, new SyncProgress(f =>
                {
                    Assert.AreEqual(thread, Thread.CurrentThread.ManagedThreadId);
                    seen.Add(f);
                }));
                Assert.IsNotEmpty(seen);
                Assert.IsTrue(seen.All(f => f >= 0.0 && f <= 1.0));
                CollectionAssert.IsOrdered(seen);
                // Without the fit there is nothing to report.
                seen.Clear();
                TilePatternEngine.Tiles(pattern, new TileOptions { Fit = false }, Surface, new SyncProgress(seen.Add));
                Assert.IsEmpty(seen);
            }
        }

        [Test]
        public void CancellingDuringTheFitThrowsWithTheToken()
        {
            using (Pattern pattern = Solve(Quads))
            using (var cts = new CancellationTokenSource())
            {
                int calls = 0;
                var progress = new SyncProgress(f =>
                {
                    if (++calls == 2)
                        cts.Cancel();
                });
                var e = Assert.Throws<TilePatternCanceledException>(() => TilePatternEngine.Tiles(pattern, new TileOptions(), Surface, progress, cts.Token));
                Assert.AreEqual(cts.Token, e.CancellationToken);
                Assert.AreEqual(TilePatternStatus.Cancelled, e.Status);
                StringAssert.Contains("cancelled", e.NativeMessage);
                Assert.AreEqual(2, calls, "no progress after the cancel");
                // The other copy of the mesh too, and an already cancelled token before the call.
                Assert.Throws<TilePatternCanceledException>(() => TilePatternEngine.Tiles(Quads, pattern, new TileOptions(), Surface, null, cts.Token));
                // The pattern is unharmed.
                Assert.IsNotEmpty(TilePatternEngine.Tiles(pattern, new TileOptions(), Surface, null, CancellationToken.None).Tiles);
            }
        }

        [Test]
        public void AnExceptionInTheFitsProgressIsRethrownAfterTheCall()
        {
            using (Pattern pattern = Solve(Quads))
            {
                var e = Assert.Throws<InvalidOperationException>(() => TilePatternEngine.Tiles(pattern, new TileOptions(), Surface,
                    new SyncProgress(f => { throw new InvalidOperationException("sink failed in the fit"); })));
                Assert.AreEqual("sink failed in the fit", e.Message);
            }
        }

        [MethodImpl(MethodImplOptions.NoInlining)]
        static string ReportWithOldStruct(Pattern pattern, bool abi2)
        {
            TpTileOptions native = new TileOptions().ToNative();
            native.fit = 0; // beyond an ABI 2 struct: only read when the struct is long enough
            if (abi2)
                native.struct_size = (uint)Marshal.OffsetOf(typeof(TpTileOptions), "fit");
            TilesHandle tiles;
            int status = NativeMethods.tp_tiles_build_with_progress_without_surface(pattern.MeshHandle, pattern.Handle, IntPtr.Zero, ref native, null, IntPtr.Zero, out tiles);
            using (tiles)
            {
                Native.Check(status);
                return TilePatternEngine.ReportJson(tiles);
            }
        }

        [Test]
        public void AnAbi2SizedTileOptionsStructKeepsTheFitOn()
        {
            using (Pattern pattern = Solve(TestMeshes.Grid(6, 4, 0.145)))
            {
                Assert.IsNotNull(Report.Parse(ReportWithOldStruct(pattern, true)).Fit, "fit = 0 beyond the ABI 2 struct is not read");
                Assert.IsNull(Report.Parse(ReportWithOldStruct(pattern, false)).Fit, "the full struct's fit = 0 is read");
            }
        }

        [Test]
        public void WhatCannotFitIsCutAndLabelledC()
        {
            using (Pattern pattern = Solve(WaveQuads))
            {
                var tile = new TileOptions();
                Tiling tiling = TilePatternEngine.Tiles(pattern, tile, Wave);
                Assert.Greater(tiling.FitCutCount, 0);
                Assert.GreaterOrEqual(tiling.Report.Joints.FitCuts, tiling.FitCutCount);
                foreach (Tile t in tiling.Tiles.Where(t => t.Kind == TileKind.FitCut))
                {
                    StringAssert.StartsWith("C", t.Label);
                    Assert.IsNotEmpty(t.Outline);
                    Assert.That(t.KeptFraction, Is.GreaterThan(0.0).And.LessThan(1.0));
                    Assert.IsNotEmpty(TilePieces.Of(t), "a fit cut makes solid pieces like a boundary cut");
                }
                CutGroup c1 = tiling.CutList.Single(g => g.Label == "C1");
                Assert.AreEqual("fit_cut", c1.Kind);
                Assert.AreEqual("fit_cut", TileOutputs<string>.KindName(TileKind.FitCut));
                Assert.LessOrEqual(tiling.Report.Joints.MaxOverlap, tile.Joint / 20 + 1e-12, "no two tiles overlap by more than the tolerance");
            }
        }

        [Test]
        public void LevelCoursesRemeshAtACoursesHeightAndFitBetter()
        {
            // The CLI's route: level courses on quads of max((L + joint) / 2, W + joint).
            var tile = new TileOptions();
            PolyMesh levelQuads = TilePatternEngine.Remesh(Surface, RemeshOptions.ForTile(tile, Courses.Level));
            using (Pattern level = Solve(levelQuads, new PatternOptions { TimeLimitSeconds = 5, Courses = Courses.Level }))
            {
                Tiling tiling = TilePatternEngine.Tiles(level, tile, Surface);
                Assert.IsNotNull(tiling.Report.Fit);
                Assert.Less(tiling.Report.Joints.P95Deviation, 0.005, "p95 |gap - joint| under 5 mm");
            }
        }

        [Test]
        public void DefaultsInADocumentsUnits()
        {
            Assert.AreEqual(1.0, TileDefaults.For("Millimeters").UnitsPerMm);
            Assert.AreEqual(0.001, TileDefaults.For("Meters").UnitsPerMm, 1e-18);
            Assert.AreEqual(1 / 304.8, TileDefaults.For("Feet").UnitsPerMm, 1e-15);
            Assert.AreEqual(1.0, TileDefaults.For("CustomUnits").UnitsPerMm, "millimetres when the units have no fixed length");
            TileDefaults mm = TileDefaults.For("Millimeters");
            TileOptions o = mm.ToTileOptions();
            Assert.AreEqual(1.0, o.UnitsPerMm);
            Assert.IsTrue(o.Fit);
            Assert.AreEqual(145.0, mm.QuadEdgeFor(Courses.Free), 1e-12);
            Assert.AreEqual(150.0, mm.QuadEdgeFor(Courses.Level), 1e-12);
            Assert.AreEqual(150.0, o.QuadEdge(Courses.Level), 1e-12);
            Assert.AreEqual(145.0, TileOptions.QuadEdgeOf(280, 100, 10, Courses.Level), 1e-12, "a course lower than the square quad keeps the square");
        }

        static Report JointsReport(string fit, int overlaps, double maxOverlap)
        {
            return Report.Parse("{\"tile\": {\"length\": 0.28, \"width\": 0.14, \"thickness\": 0.015, \"joint\": 0.01},"
                + "\"joints\": {\"contacts\": 10, \"joint\": 0.01, \"p95_deviation\": 0.002, \"overlaps\": " + overlaps
                + ", \"max_overlap\": " + maxOverlap.ToString(System.Globalization.CultureInfo.InvariantCulture) + ", \"fit_cuts\": 3"
                + (fit == null ? "" : ", \"before_fit\": {\"contacts\": 10, \"p95_deviation\": 0.02}") + "}"
                + (fit == null ? "" : ", \"fit\": {\"status\": \"" + fit + "\", \"iterations\": 12, \"overlap_tolerance\": 0.0005}") + "}");
        }

        [Test]
        public void MessagesAboutTheJoints()
        {
            // Fitted, overlaps within a twentieth of the joint: remarks only.
            UserMessage[] m = UserMessage.ForJoints(JointsReport("converged", 2, 0.0004));
            Assert.AreEqual(2, m.Length);
            Assert.IsTrue(m.All(x => x.Level == MessageLevel.Remark), string.Join(" | ", m.Select(x => x.ToString()).ToArray()));
            StringAssert.Contains("converged, 12 steps", m[0].Text);
            StringAssert.Contains("0.02 before, 0.002 after", m[0].Text);
            StringAssert.Contains("3 tiles cut", m[0].Text);
            StringAssert.Contains("2 pairs of tiles overlap by at most 0.0004", m[1].Text);
            // A deeper overlap, and a fit cut short by its time limit: warnings.
            m = UserMessage.ForJoints(JointsReport("time_limit", 1, 0.003));
            Assert.AreEqual(MessageLevel.Warning, m[0].Level);
            StringAssert.Contains("time limit", m[0].Text);
            Assert.AreEqual(MessageLevel.Warning, m[1].Level);
            StringAssert.Contains("the deepest by 0.003", m[1].Text);
            // Without the fit any overlap is a warning that names the fit; no overlap, no message.
            m = UserMessage.ForJoints(JointsReport(null, 4, 0.0001));
            Assert.AreEqual(1, m.Length);
            Assert.AreEqual(MessageLevel.Warning, m[0].Level);
            StringAssert.Contains("turn the fit on", m[0].Text);
            Assert.IsEmpty(UserMessage.ForJoints(JointsReport(null, 0, 0.0)));
            Assert.Throws<ArgumentNullException>(() => UserMessage.ForJoints(null));
        }

        [Test]
        public void MessageAboutTheLayingOrder()
        {
            Report r = Report.Parse("{\"sequence\": {\"support_tiles\": 16, \"unsupported\": 4, \"support\": \"edges\", \"sloped_tiles\": 102, \"climbing_tiles\": 56}}");
            Assert.AreEqual(102, r.Sequence.SlopedTiles);
            Assert.AreEqual(56, r.Sequence.ClimbingTiles);
            UserMessage m = UserMessage.ForLaying(r);
            Assert.AreEqual(MessageLevel.Remark, m.Level);
            Assert.AreEqual("Laying order: 16 tiles on the supports, 4 need a prop; 56 of the 102 whole tiles on slopes over 20 degrees run up them.", m.Text);
            // No slope, no count; no laying order (an older library's report), no message.
            r = Report.Parse("{\"sequence\": {\"support_tiles\": 3, \"unsupported\": 0, \"support\": \"level\"}}");
            Assert.AreEqual("Laying order: 3 tiles on the supports, 0 need a prop.", UserMessage.ForLaying(r).Text);
            Assert.IsNull(UserMessage.ForLaying(Report.Parse("{\"faces\": 10}")));
            Assert.Throws<ArgumentNullException>(() => UserMessage.ForLaying(null));
        }

        [Test]
        public void FitReportFromJson()
        {
            Report r = Report.Parse("{\"joints\": {\"contacts\": 3, \"joint\": 0.01, \"within_2mm\": 0.5, \"within_5mm\": 0.75, \"fit_cuts\": 2,"
                + "\"before_fit\": {\"contacts\": 3, \"joint\": 0.01, \"p95_deviation\": 0.02}},"
                + "\"fit\": {\"status\": \"iteration_limit\", \"iterations\": 60, \"objective_before\": 2.0, \"objective_after\": 1.0, \"mean_move\": 0.01, \"max_move\": 0.03, \"room_pieces\": 4},"
                + "\"seconds\": {\"pattern\": 0.5, \"tiles\": 0.2, \"fit\": 0.1}}");
            Assert.AreEqual(0.5, r.Joints.Within2Mm);
            Assert.AreEqual(0.75, r.Joints.Within5Mm);
            Assert.AreEqual(2, r.Joints.FitCuts);
            Assert.AreEqual(0.02, r.Joints.BeforeFit.P95Deviation);
            Assert.AreEqual(FitStatus.IterationLimit, r.Fit.Status);
            Assert.AreEqual(60, r.Fit.Iterations);
            Assert.AreEqual(0.03, r.Fit.MaxMove);
            Assert.AreEqual(4, r.Fit.RoomPieces);
            Assert.AreEqual(0.1, r.FitSeconds);
            Assert.AreEqual(FitStatus.Unknown, Report.Parse("{\"fit\": {\"status\": \"something_new\"}}").Fit.Status);
            Assert.AreEqual(0, Report.Parse("{\"fit\": {\"status\": \"converged\"}}").Fit.RoomPieces);
            Assert.IsNull(Report.Parse("{\"joints\": {}}").Fit);
        }
    }
}

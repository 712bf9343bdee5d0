// What the Grasshopper components leave to the wrapper: defaults in the document's units,
// tree paths, the parallel tile outputs, the pieces of cut tiles, input fingerprints,
// background jobs, messages, memory pressure and the plug-in folder.
using System;
using System.Collections.Generic;
using System.Linq;
using System.Threading;
using NUnit.Framework;

namespace TilePattern.Tests
{
    [TestFixture]
    public class HostTests
    {
        // ---- defaults in the document's units ------------------------------------------------

        [Test]
        public void DefaultsInAMillimetreDocumentAre280By140By15Joint10()
        {
            TileDefaults d = TileDefaults.For("Millimeters");
            Assert.IsTrue(d.UnitsKnown);
            Assert.AreEqual(280.0, d.Length, 1e-12);
            Assert.AreEqual(140.0, d.Width, 1e-12);
            Assert.AreEqual(15.0, d.Thickness, 1e-12);
            Assert.AreEqual(10.0, d.Joint, 1e-12);
            Assert.AreEqual(145.0, d.QuadEdge, 1e-12);
            TileOptions o = d.ToTileOptions();
            Assert.AreEqual(new[] { 280.0, 140.0, 15.0, 10.0 }, new[] { o.Length, o.Width, o.Thickness, o.Joint });
        }

        [TestCase("Meters", 0.28, 0.14, 0.015, 0.01)]
        [TestCase("Centimeters", 28.0, 14.0, 1.5, 1.0)]
        [TestCase("Millimeters", 280.0, 140.0, 15.0, 10.0)]
        [TestCase("Inches", 280 / 25.4, 140 / 25.4, 15 / 25.4, 10 / 25.4)]
        [TestCase("Feet", 280 / 304.8, 140 / 304.8, 15 / 304.8, 10 / 304.8)]
        public void DefaultsFollowTheUnitSystem(string units, double length, double width, double thickness, double joint)
        {
            TileDefaults d = TileDefaults.For(units);
            Assert.IsTrue(d.UnitsKnown, units);
            Assert.AreEqual(length, d.Length, 1e-12 * length);
            Assert.AreEqual(width, d.Width, 1e-12 * width);
            Assert.AreEqual(thickness, d.Thickness, 1e-12 * thickness);
            Assert.AreEqual(joint, d.Joint, 1e-12 * joint);
        }

        [TestCase(null)]
        [TestCase("None")]
        [TestCase("CustomUnits")]
        [TestCase("Unset")]
        public void UnitsWithoutALengthFallBackToMillimetres(string units)
        {
            TileDefaults d = TileDefaults.For(units);
            Assert.IsFalse(d.UnitsKnown);
            Assert.AreEqual(280.0, d.Length);
            Assert.IsNaN(ModelUnits.MillimetresPerUnit(units));
        }

        // ---- tree paths ----------------------------------------------------------------------

        [Test]
        public void TwoMeshesIntoTilePatternGiveDisjointPairPaths()
        {
            // Two meshes solved in one component: both in one list (same target path {0},
            // target index 0 and 1), and in two branches ({0} and {1}, index 0 each).
            int[] counts;
            using (Pattern a = TilePatternEngine.Match(TestMeshes.Grid(4, 4)))
            using (Pattern b = TilePatternEngine.Match(TestMeshes.Grid(6, 2)))
                counts = new[] { a.Pairs.Length, b.Pairs.Length };
            Assert.Greater(counts[0], 4);
            Assert.Greater(counts[1], 2);
            foreach (int[][] targets in new[] { new[] { new[] { 0 }, new[] { 0 } }, new[] { new[] { 0 }, new[] { 1 } } })
            {
                bool sameBranch = targets[0][0] == targets[1][0];
                var first = TreePaths.Branches(targets[0], 0, counts[0]).Select(TreePaths.Format).ToList();
                var second = TreePaths.Branches(targets[1], sameBranch ? 1 : 0, counts[1]).Select(TreePaths.Format).ToList();
                Assert.AreEqual(counts[0], first.Distinct().Count());
                Assert.AreEqual(counts[1], second.Distinct().Count());
                CollectionAssert.IsEmpty(first.Intersect(second), "no branch holds pairs of both meshes");
            }
            Assert.AreEqual("{0;1;5}", TreePaths.Format(TreePaths.Branch(new[] { 0 }, 1, 5)));
            Assert.AreEqual("{2;0;3;0}", TreePaths.Format(TreePaths.Branch(new[] { 2, 0 }, 3, 0)));
        }

        // ---- the parallel tile outputs -------------------------------------------------------

        static Tiling CutTiling(out Pattern pattern)
        {
            // Quads reach x = 10, the surface ends at x = 6.5: boundary tiles (PipelineTests).
            pattern = TilePatternEngine.Match(TestMeshes.Grid(10, 10), new PatternOptions { Weight = 2.0 });
            var tile = new TileOptions { Length = 1.9, Width = 0.95, Thickness = 0.1, Joint = 0.1 };
            return TilePatternEngine.Tiles(pattern, tile, TestMeshes.Grid(13, 20, 0.5));
        }

        [Test]
        public void TileOutputsLineUpOneToOne()
        {
            Pattern pattern;
            Tiling tiling = CutTiling(out pattern);
            using (pattern)
            {
                Assert.Greater(tiling.BoundaryCount, 0);
                TileOutputs<string> o = TileOutputs<string>.Build(tiling, (t, pieces) =>
                {
                    if (t.Index == 3)
                        return null;                          // geometry that fails quietly
                    if (t.Index == 5)
                        throw new InvalidOperationException("no solid");
                    return t.Label + "#" + t.Index + "/" + pieces.Length;
                });
                int n = tiling.Tiles.Length;
                Assert.AreEqual(n, o.Count);
                Assert.AreEqual(n, o.Geometry.Count);
                Assert.AreEqual(n, o.Labels.Count);
                Assert.AreEqual(n, o.Frames.Count);
                Assert.AreEqual(n, o.Steps.Count);
                Assert.AreEqual(n, o.Kinds.Count);
                for (int i = 0; i < n; i++)
                {
                    Tile t = tiling.Tiles[i];
                    Assert.AreEqual(t.Label, o.Labels[i]);
                    Assert.AreEqual(t.Step, o.Steps[i]);
                    Assert.AreEqual(TileOutputs<string>.KindName(t.Kind), o.Kinds[i]);
                    Assert.AreEqual(t.Origin, o.Frames[i].Origin);
                    Assert.AreEqual(t.XAxis, o.Frames[i].XAxis);
                    if (i == 3 || i == 5)
                        Assert.IsNull(o.Geometry[i], "a failed tile keeps its slot, empty");
                    else
                        StringAssert.StartsWith(t.Label + "#" + i + "/", o.Geometry[i], "geometry " + i + " is tile " + i + "'s");
                }
                Assert.AreEqual(2, o.Warnings.Count);
                StringAssert.StartsWith("tile 3 (" + tiling.Tiles[3].Label, o.Warnings[0]);
                StringAssert.Contains("slot left empty", o.Warnings[0]);
                StringAssert.StartsWith("tile 5 (", o.Warnings[1]);
                StringAssert.Contains("no solid", o.Warnings[1]);
                CollectionAssert.AreEquivalent(new[] { "full", "half", "boundary" }.Where(k => o.Kinds.Contains(k)), o.Kinds.Distinct());
                CollectionAssert.Contains(o.Kinds, "boundary");
            }
        }

        [Test]
        public void EveryCutTileOfARealTilingHasClosedPieces()
        {
            Pattern pattern;
            Tiling tiling = CutTiling(out pattern);
            using (pattern)
                foreach (Tile t in tiling.Tiles)
                {
                    TilePiece[] pieces = TilePieces.Of(t);
                    if (t.Kind != TileKind.Boundary)
                    {
                        Assert.IsEmpty(pieces, "an uncut tile is its box");
                        continue;
                    }
                    Assert.IsNotEmpty(pieces, "tile " + t.Index);
                    foreach (TilePiece piece in pieces)
                        foreach (double[] loop in piece.Loops)
                            AssertClosedOnce(loop);
                }
        }

        [Test]
        public void ACutTileThatSplitsYieldsAllItsPiecesWithTheirHoles()
        {
            // Two kept pieces (counter-clockwise squares) left and right of a cut, the right one
            // with a hole (clockwise); the first loop repeats its first point at the end and one
            // point twice in a row.
            var tile = new Tile
            {
                Index = 7,
                Kind = TileKind.Boundary,
                Label = "B2",
                Faces = new[] { 4, 5 },
                Origin = new[] { 10.0, 20.0, 30.0 },
                XAxis = new[] { 0.0, 1.0, 0.0 },
                YAxis = new[] { -1.0, 0.0, 0.0 },
                ZAxis = new[] { 0.0, 0.0, 1.0 },
                Length = 2.8, Width = 1.4, Thickness = 0.15,
                Corners = new double[24],
                Outline = new[]
                {
                    new[] { -1.4, -0.7, -0.2, -0.7, -0.2, -0.7, -0.2, 0.7, -1.4, 0.7, -1.4, -0.7 },
                    new[] { 0.2, -0.7, 1.4, -0.7, 1.4, 0.7, 0.2, 0.7 },
                    new[] { 0.6, -0.2, 0.6, 0.2, 1.0, 0.2, 1.0, -0.2 },
                },
            };
            TilePiece[] pieces = TilePieces.Of(tile);
            Assert.AreEqual(2, pieces.Length, "both pieces of the split tile");
            Assert.AreEqual(0, pieces[0].Holes.Length);
            Assert.AreEqual(1, pieces[1].Holes.Length, "the hole belongs to the piece around it");
            Assert.AreEqual(3 * 5, pieces[0].Outer.Length, "4 corners and the closing point once");
            foreach (TilePiece p in pieces)
                foreach (double[] loop in p.Loops)
                    AssertClosedOnce(loop);
            // In model coordinates: origin + x * XAxis + y * YAxis on the bottom face.
            Assert.AreEqual(new[] { 10.0 + 0.7, 20.0 - 1.4, 30.0 }, pieces[0].Outer.Take(3).ToArray());
            Assert.AreEqual(new[] { 0.0, 0.0, 0.15 }, TilePieces.Extrusion(tile));

            TileOutputs<string> o = TileOutputs<string>.Build(new Tiling(new[] { tile }, null, "[]"), (t, p) => p.Length + " pieces");
            Assert.AreEqual(new[] { "2 pieces" }, o.Geometry.ToArray());
            Assert.IsEmpty(o.Warnings);
        }

        static void AssertClosedOnce(double[] xyz)
        {
            int n = xyz.Length / 3;
            Assert.GreaterOrEqual(n, 4, "3 points and the closing point");
            for (int d = 0; d < 3; d++)
                Assert.AreEqual(xyz[d], xyz[3 * (n - 1) + d], "closed");
            for (int p = 1; p < n; p++)
                Assert.IsFalse(Enumerable.Range(0, 3).All(d => Math.Abs(xyz[3 * p + d] - xyz[3 * (p - 1) + d]) < 1e-12), "no point twice in a row (point " + p + ")");
        }

        // ---- input fingerprints --------------------------------------------------------------

        [Test]
        public void InputKeysTellInputsApart()
        {
            Func<PolyMesh, double, string> key = (m, x) => new InputKey().Add(m).Add(x).Add(1).Add(true).Add("s").Add(new[] { 1, 2 }).ToString();
            string k = key(TestMeshes.Grid(3, 3), 0.5);
            Assert.AreEqual(k, key(TestMeshes.Grid(3, 3), 0.5), "same inputs, same key");
            Assert.AreNotEqual(k, key(TestMeshes.Grid(3, 3), 0.25));
            Assert.AreNotEqual(k, key(TestMeshes.Grid(3, 3, 1.001), 0.5));
            Assert.AreNotEqual(k, key(TestMeshes.Grid(4, 3), 0.5));
            Assert.AreNotEqual(new InputKey().Add(1).Add(2).ToString(), new InputKey().Add(2).Add(1).ToString());
        }

        // ---- background jobs -----------------------------------------------------------------

        [Test]
        public void AJobRunsInTheBackgroundAndIsReadOnTheNextPass()
        {
            var finished = new SemaphoreSlim(0);
            var release = new ManualResetEventSlim();
            int caller = Thread.CurrentThread.ManagedThreadId, worker = -1;
            using (var jobs = new BackgroundJobs<string>(() => finished.Release()))
            {
                Func<CancellationToken, IProgress<double>, string> work = (token, progress) =>
                {
                    worker = Thread.CurrentThread.ManagedThreadId;
                    progress.Report(0.5);
                    release.Wait(5000);
                    return "result";
                };
                jobs.BeginPass();
                JobStatus<string> s = jobs.Request(0, "k", work);
                jobs.EndPass();
                Assert.AreEqual(JobState.Running, s.State, "Request returns at once");
                Assert.AreEqual(1, jobs.RunningCount);
                release.Set();
                Assert.IsTrue(finished.Wait(5000), "the host is told when it ends");
                Assert.AreNotEqual(caller, worker, "the work ran on another thread");
                jobs.BeginPass();
                s = jobs.Request(0, "k", (t, p) => { Assert.Fail("same inputs: no new job"); return null; });
                jobs.EndPass();
                Assert.AreEqual(JobState.Done, s.State);
                Assert.AreEqual("result", s.Result);
                Assert.AreEqual("", jobs.Summary);
            }
        }

        [Test]
        public void NewInputsCancelTheOldJobAndOnlyTheCurrentOneIsReported()
        {
            var finished = new SemaphoreSlim(0);
            var firstCancelled = new ManualResetEventSlim();
            using (var jobs = new BackgroundJobs<string>(() => finished.Release()))
            {
                jobs.BeginPass();
                jobs.Request(0, "old", (token, p) =>
                {
                    if (token.WaitHandle.WaitOne(5000))
                        firstCancelled.Set();
                    token.ThrowIfCancellationRequested();
                    return "old";
                });
                jobs.EndPass();
                jobs.BeginPass();
                JobStatus<string> s = jobs.Request(0, "new", (token, p) => "new");
                jobs.EndPass();
                Assert.AreEqual("new", s.Key);
                Assert.IsTrue(firstCancelled.Wait(5000), "the old job's token was cancelled");
                Assert.IsTrue(finished.Wait(5000));
                Assert.IsTrue(jobs.Wait(5000));
                Assert.IsFalse(finished.Wait(200), "the replaced job's end is not reported");
                jobs.BeginPass();
                Assert.AreEqual("new", jobs.Request(0, "new", (t, p) => null).Result);
                jobs.EndPass();
            }
        }

        [Test]
        public void SlotsNoLongerAskedForAreCancelled()
        {
            var cancelled = new CountdownEvent(2);
            using (var jobs = new BackgroundJobs<int>(() => { }))
            {
                Func<CancellationToken, IProgress<double>, int> wait = (token, p) =>
                {
                    if (token.WaitHandle.WaitOne(5000))
                        cancelled.Signal();
                    return 0;
                };
                jobs.BeginPass();
                for (int i = 0; i < 3; i++)
                    jobs.Request(i, "k" + i, wait);
                jobs.EndPass();
                jobs.BeginPass();
                jobs.Request(0, "k0", wait);   // one mesh left
                jobs.EndPass();
                Assert.IsTrue(cancelled.Wait(5000), "slots 1 and 2 were cancelled");
                Assert.AreEqual(1, jobs.RunningCount);
            }
        }

        [Test]
        public void CancelOnRequestStaysCancelledUntilRestart()
        {
            var finished = new SemaphoreSlim(0);
            int starts = 0;
            using (var jobs = new BackgroundJobs<string>(() => finished.Release()))
            {
                Func<CancellationToken, IProgress<double>, string> work = (token, p) =>
                {
                    Interlocked.Increment(ref starts);
                    token.WaitHandle.WaitOne(5000);
                    token.ThrowIfCancellationRequested();
                    return "x";
                };
                jobs.BeginPass();
                jobs.Request(0, "k", work);
                jobs.EndPass();
                StringAssert.StartsWith("Solving", jobs.Summary);
                Assert.AreEqual(1, jobs.CancelAll());
                Assert.IsTrue(finished.Wait(5000), "the host hears of the cancelled job");
                jobs.BeginPass();
                Assert.AreEqual(JobState.Cancelled, jobs.Request(0, "k", work).State, "no restart for the same inputs");
                jobs.EndPass();
                Assert.AreEqual("Cancelled", jobs.Summary);
                Assert.AreEqual(1, starts);
                jobs.Restart();
                jobs.BeginPass();
                Assert.AreEqual(JobState.Running, jobs.Request(0, "k", work).State);
                jobs.EndPass();
                jobs.CancelAll();
                Assert.IsTrue(jobs.Wait(5000));
                Assert.AreEqual(2, starts);
            }
        }

        [Test]
        public void FailuresAndProgressAreKept()
        {
            var finished = new SemaphoreSlim(0);
            var progressed = new SemaphoreSlim(0);
            var go = new ManualResetEventSlim();
            using (var jobs = new BackgroundJobs<int>(() => finished.Release(), () => progressed.Release(), 0.0))
            {
                jobs.BeginPass();
                jobs.Request(0, "k", (token, p) => { p.Report(0.25); go.Wait(5000); throw new InvalidMeshException("face 3 is bad"); });
                jobs.EndPass();
                Assert.IsTrue(progressed.Wait(5000), "progress is passed on");
                Assert.AreEqual("Solving… 25 %", jobs.Summary);
                go.Set();
                Assert.IsTrue(finished.Wait(5000));
                jobs.BeginPass();
                JobStatus<int> s = jobs.Request(0, "k", (t, p) => 1);
                jobs.EndPass();
                Assert.AreEqual(JobState.Failed, s.State);
                Assert.IsInstanceOf<InvalidMeshException>(s.Error);
                Assert.AreEqual(MessageLevel.Error, UserMessage.For(s.Error).Level);
                StringAssert.Contains("face 3 is bad", UserMessage.For(s.Error).Text);
            }
        }

        [Test]
        public void ARealMatchIsCancelledFromTheJobs()
        {
            // The native solve runs on the worker and stops when the inputs change.
            PolyMesh big = TestMeshes.Grid(100, 100);
            var finished = new SemaphoreSlim(0);
            using (var jobs = new BackgroundJobs<Pattern>(() => finished.Release()))
            {
                Exception seen = null;
                var ended = new ManualResetEventSlim();
                jobs.BeginPass();
                jobs.Request(0, "big", (token, progress) =>
                {
                    try
                    {
                        return TilePatternEngine.Match(big, new PatternOptions { TimeLimitSeconds = 60 }, progress, token);
                    }
                    catch (Exception e)
                    {
                        seen = e;
                        throw;
                    }
                    finally
                    {
                        ended.Set();
                    }
                });
                jobs.EndPass();
                Thread.Sleep(300);
                var watch = System.Diagnostics.Stopwatch.StartNew();
                jobs.BeginPass();
                jobs.Request(0, "small", (token, progress) => TilePatternEngine.Match(TestMeshes.Grid(2, 2), null, progress, token));
                jobs.EndPass();
                Assert.IsTrue(ended.Wait(10000));
                Assert.Less(watch.Elapsed.TotalSeconds, 5.0);
                Assert.IsInstanceOf<TilePatternCanceledException>(seen);
                Assert.IsTrue(finished.Wait(10000));
                jobs.BeginPass();
                using (Pattern p = jobs.Request(0, "small", (t, q) => null).Result)
                    Assert.AreEqual(2, p.Pairs.Length);
                jobs.EndPass();
            }
        }

        // ---- messages ------------------------------------------------------------------------

        [Test]
        public void StaleOrForeignNativeLibrariesGetClearMessages()
        {
            UserMessage stale = UserMessage.For(new EntryPointNotFoundException("Unable to find an entry point named 'tp_tiles_labels'"));
            Assert.AreEqual(MessageLevel.Error, stale.Level);
            StringAssert.Contains("lacks a function the plug-in calls", stale.Text);
            StringAssert.Contains("tp_tiles_labels", stale.Text);
            StringAssert.Contains("same release", stale.Text);
            UserMessage foreign = UserMessage.For(new BadImageFormatException("An attempt was made to load a program with an incorrect format."));
            StringAssert.Contains("built for another processor or operating system", foreign.Text);
            Assert.AreEqual(MessageLevel.Warning, UserMessage.For(new TilePatternCanceledException("stop", CancellationToken.None)).Level);
            Assert.AreEqual(MessageLevel.Warning, UserMessage.For(new AggregateException(new OperationCanceledException())).Level);
        }

        // ---- memory pressure -----------------------------------------------------------------

        [Test]
        public void PatternsAnnounceTheirNativeMemoryUntilReleased()
        {
            GC.Collect();
            GC.WaitForPendingFinalizers();
            long before = NativePressure.Outstanding;
            Pattern p = TilePatternEngine.Match(TestMeshes.Grid(20, 20));
            long estimate = p.NativeBytesEstimate;
            Assert.Greater(estimate, 24L * 441, "at least the mesh's coordinates");
            Assert.AreEqual(before + estimate, NativePressure.Outstanding);
            p.Dispose();
            Assert.AreEqual(before, NativePressure.Outstanding, "released with the handles");
            Assert.AreEqual(0, p.NativeBytesEstimate);
        }

        // ---- the plug-in folder --------------------------------------------------------------

        [Test]
        public void ThePluginFolderComesFromTheHostWhenTheAssemblyHasNoLocation()
        {
            string gha = System.IO.Path.Combine(System.IO.Path.Combine("plugins", "TilePattern"), "TilePattern.Grasshopper.gha");
            Assert.AreEqual(System.IO.Path.Combine("plugins", "TilePattern"), PluginLocation.Folder(gha, ""), "loaded from bytes: Location is empty");
            Assert.AreEqual("lib", PluginLocation.Folder(null, System.IO.Path.Combine("lib", "TilePattern.dll")));
            Assert.IsNull(PluginLocation.Folder("", null));
        }
    }
}

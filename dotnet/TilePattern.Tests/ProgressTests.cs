// Progress, cancellation and time limits through the native callback.
using System;
using System.Collections.Generic;
using System.Diagnostics;
using System.Threading;
using NUnit.Framework;

namespace TilePattern.Tests
{
    [TestFixture]
    public class ProgressTests
    {
        static PolyMesh big;

        // 100 x 100 quads: the staggered solve takes seconds, long enough to cancel.
        static PolyMesh Big
        {
            get { return big ?? (big = TestMeshes.Grid(100, 100)); }
        }

        [Test]
        public void CancellationTokenStopsTheSolve()
        {
            using (var cts = new CancellationTokenSource())
            {
                cts.CancelAfter(300);
                var watch = Stopwatch.StartNew();
                var e = Assert.Throws<TilePatternCanceledException>(() => TilePatternEngine.Match(Big, new PatternOptions { TimeLimitSeconds = 60 }, null, cts.Token));
                Assert.Less(watch.Elapsed.TotalSeconds, 5.0, "cancelled within about a second of the request");
                Assert.AreEqual(cts.Token, e.CancellationToken);
                Assert.AreEqual(TilePatternStatus.Cancelled, e.Status);
                StringAssert.Contains("cancelled", e.NativeMessage);
                Assert.IsInstanceOf<OperationCanceledException>(e);
            }
        }

        [Test]
        public void ProgressDrivenCancel()
        {
            using (var cts = new CancellationTokenSource())
            {
                var seen = new List<double>();
                int thread = Thread.CurrentThread.ManagedThreadId;
                var progress = new SyncProgress(f =>
                {
                    Assert.AreEqual(thread, Thread.CurrentThread.ManagedThreadId, "called on the calling thread");
                    seen.Add(f);
                    if (seen.Count == 3)
                        cts.Cancel();
                });
                Assert.Throws<TilePatternCanceledException>(() => TilePatternEngine.Match(Big, new PatternOptions { TimeLimitSeconds = 60 }, progress, cts.Token));
                Assert.AreEqual(3, seen.Count, "no progress after the cancel");
                for (int i = 0; i < seen.Count; i++)
                {
                    Assert.That(seen[i], Is.InRange(0.0, 1.0));
                    if (i > 0)
                        Assert.That(seen[i], Is.GreaterThanOrEqualTo(seen[i - 1]));
                }
            }
        }

        // The paper's whole program on CBC for a 12 x 12 grid; its time in seconds.
        static double TimedSmallMip()
        {
            var watch = Stopwatch.StartNew();
            TilePatternEngine.Match(TestMeshes.Grid(12, 12), new PatternOptions { Method = SolveMethod.Mip, TimeLimitSeconds = 60 });
            return watch.Elapsed.TotalSeconds;
        }

        // Cancel from the progress callback in the middle of the whole program on CBC (45 x 45
        // grid, 2025 faces, whose root linear program alone takes CBC seconds) returns within
        // 0.2 s and leaves CBC free: a CBC solve right after takes as long as before the cancel.
        [Test]
        public void CancelInsideCbcReturnsAtOnceAndLeavesCbcFree()
        {
            double before = TimedSmallMip();
            using (var cts = new CancellationTokenSource())
            {
                var solving = Stopwatch.StartNew();
                var asked = new Stopwatch();
                // The callbacks of this solve come only while CBC runs: cancel a second into it.
                var progress = new SyncProgress(f =>
                {
                    if (solving.Elapsed.TotalSeconds >= 1.0 && !asked.IsRunning)
                    {
                        asked.Start();
                        cts.Cancel();
                    }
                });
                var options = new PatternOptions { Method = SolveMethod.Mip, TimeLimitSeconds = 60 };
                Assert.Throws<TilePatternCanceledException>(() => TilePatternEngine.Match(TestMeshes.Grid(45, 45), options, progress, cts.Token));
                Assert.IsTrue(asked.IsRunning, "cancelled from the callback");
                Assert.Less(asked.Elapsed.TotalSeconds, 0.2, "returned within 0.2 s of the cancel");
            }
            double after = TimedSmallMip();
            // Generous for a loaded machine; a CBC still busy with the cancelled solve would hold
            // the next one up for seconds.
            Assert.Less(after, 2.0 * before + 0.25, "the next CBC solve took " + after + " s, " + before + " s before");
        }

        [Test]
        public void AlreadyCancelledTokenThrowsBeforeTheCall()
        {
            var watch = Stopwatch.StartNew();
            var token = new CancellationToken(true);
            var e = Assert.Throws<TilePatternCanceledException>(() => TilePatternEngine.Match(Big, null, null, token));
            Assert.AreEqual(token, e.CancellationToken);
            Assert.Throws<TilePatternCanceledException>(() => TilePatternEngine.Remesh(TestMeshes.CurvedTriangles(4, 1, 0.1), null, null, token));
            Assert.Less(watch.Elapsed.TotalSeconds, 1.0);
        }

        [Test]
        public void RemeshCancelledAtItsStart()
        {
            // A progress sink that cancels at the first report stops the stage at its start.
            using (var cts = new CancellationTokenSource())
            {
                var progress = new SyncProgress(f => cts.Cancel());
                var e = Assert.Throws<TilePatternCanceledException>(
                    () => TilePatternEngine.Remesh(TestMeshes.CurvedTriangles(10, 1, 0.1), null, progress, cts.Token));
                StringAssert.Contains("cancelled", e.NativeMessage);
            }
        }

        [Test]
        public void RemeshCancelledMidwayAndItsTimeLimit()
        {
            // The remesh stage reports progress throughout: cancelling once past a third stops it.
            PolyMesh surface = TestMeshes.CurvedTriangles(40, 1.5, 0.3);
            var options = new RemeshOptions { TargetEdge = 0.05 };
            using (var cts = new CancellationTokenSource())
            {
                double last = 0.0;
                var progress = new SyncProgress(f => { last = f; if (f > 0.3) cts.Cancel(); });
                Assert.Throws<TilePatternCanceledException>(() => TilePatternEngine.Remesh(surface, options, progress, cts.Token));
                Assert.That(last, Is.InRange(0.3, 0.999), "cancelled during the stage, not at its end");
            }
            // A zero time limit leaves no time to build a quad mesh: a time-limit error, not a hang.
            options.TimeLimitSeconds = 0.0;
            Assert.Throws<SolverTimeLimitException>(() => TilePatternEngine.Remesh(surface, options));
        }

        [Test]
        public void ExceptionInProgressSinkIsRethrownAfterTheNativeCallReturns()
        {
            var progress = new SyncProgress(f => { throw new InvalidOperationException("sink failed"); });
            var e = Assert.Throws<InvalidOperationException>(() => TilePatternEngine.Match(Big, new PatternOptions { TimeLimitSeconds = 60 }, progress));
            Assert.AreEqual("sink failed", e.Message);
            StringAssert.Contains("SyncProgress", e.StackTrace, "the original stack trace is kept");
            var r = Assert.Throws<InvalidOperationException>(() => TilePatternEngine.Remesh(TestMeshes.CurvedTriangles(10, 1, 0.1), null, progress));
            Assert.AreEqual("sink failed", r.Message);
            // The library is unharmed.
            using (Pattern p = TilePatternEngine.Match(TestMeshes.Grid(4, 4), null, new SyncProgress(f => { })))
                Assert.IsNotEmpty(p.Pairs);
        }

        [Test]
        public void TimeLimitReturnsAValidPatternWithAnHonestStatus()
        {
            var watch = Stopwatch.StartNew();
            using (Pattern pattern = TilePatternEngine.Match(Big, new PatternOptions { TimeLimitSeconds = 0.5 }))
            {
                Assert.Less(watch.Elapsed.TotalSeconds, 10.0);
                Assert.AreEqual(SolveStatus.TimeLimit, pattern.Status);
                Assert.That(pattern.Bound, Is.GreaterThanOrEqualTo(pattern.Objective));
                Assert.Greater(pattern.Pairs.Length, 4000);
                Assert.Greater(pattern.Gap, 0.0);
            }
        }

        [Test]
        public void ZeroTimeLimitReturnsTheGreedyStartAtOnce()
        {
            var watch = Stopwatch.StartNew();
            using (Pattern pattern = TilePatternEngine.Match(Big, new PatternOptions { TimeLimitSeconds = 0 }))
            {
                Assert.Less(watch.Elapsed.TotalSeconds, 5.0);
                Assert.Greater(pattern.Pairs.Length, 4000);
            }
        }

        [Test]
        public void ProgressIsReportedDuringASolve()
        {
            var seen = new List<double>();
            using (Pattern pattern = TilePatternEngine.Match(TestMeshes.Grid(30, 30), new PatternOptions { TimeLimitSeconds = 5 }, new SyncProgress(seen.Add)))
                Assert.IsNotNull(pattern);
            Assert.IsNotEmpty(seen);
        }
    }
}

// TilePatternEngine.Run (tp_run, ABI 9): one try gives the tiles of the three stages called one
// by one; three tries are listed in the report with the one kept; progress covers the whole
// run and the token cancels it; bad tries, quads named before they exist and zones not one per
// surface face are refused.
using System;
using System.Collections.Generic;
using System.Linq;
using System.Threading;
using NUnit.Framework;

namespace TilePattern.Tests
{
    [TestFixture]
    public class RunTests
    {
        // The C test's settings: level courses on quads of 0.15 (280 x 140 tiles with a 10 mm
        // joint, as `tilepattern run` remeshes for them), the library's other defaults.
        static RemeshOptions Remesh()
        {
            return new RemeshOptions { TargetEdge = 0.15 };
        }

        static PatternOptions Level()
        {
            return new PatternOptions { Courses = Courses.Level };
        }

        static PolyMesh dome;

        static PolyMesh Dome
        {
            get { return dome ?? (dome = TestMeshes.RoundDome()); }
        }

        /// <summary>The dome through Remesh, Match and Tiles one by one (once for the fixture).</summary>
        static PolyMesh stageQuads;
        static Tiling stageTiling;
        static FacePair[] stagePairs;
        static double stageObjective;

        static void StagesOneByOne()
        {
            if (stageTiling != null)
                return;
            stageQuads = TilePatternEngine.Remesh(Dome, Remesh());
            using (Pattern pattern = TilePatternEngine.Match(stageQuads, Level()))
            {
                stageTiling = TilePatternEngine.Tiles(pattern, new TileOptions(), Dome);
                stagePairs = pattern.Pairs;
                stageObjective = pattern.Objective;
            }
        }

        static bool SameMesh(PolyMesh a, PolyMesh b)
        {
            return a.Vertices.SequenceEqual(b.Vertices) && a.FaceIndices.SequenceEqual(b.FaceIndices) && a.FaceSizes.SequenceEqual(b.FaceSizes);
        }

        static void AssertSameTiles(Tiling expected, Tiling actual, string what)
        {
            Assert.AreEqual(expected.Tiles.Length, actual.Tiles.Length, what + ": tile count");
            for (int i = 0; i < expected.Tiles.Length; i++)
            {
                // Bit for bit, as the C test's memcmp.
                CollectionAssert.AreEqual(expected.Tiles[i].Corners, actual.Tiles[i].Corners, what + ": corners of tile " + i);
                Assert.AreEqual(expected.Tiles[i].Kind, actual.Tiles[i].Kind, what + ": kind of tile " + i);
                Assert.AreEqual(expected.Tiles[i].Label, actual.Tiles[i].Label, what + ": label of tile " + i);
                Assert.AreEqual(expected.Tiles[i].Step, actual.Tiles[i].Step, what + ": step of tile " + i);
            }
        }

        [Test]
        public void OneTryGivesTheTilesOfTheStagesOneByOne()
        {
            StagesOneByOne();
            Assert.Greater(stageTiling.Tiles.Length, 100);
            var seen = new List<double>();
            int thread = Thread.CurrentThread.ManagedThreadId;
            var progress = new SyncProgress(f =>
            {
                Assert.AreEqual(thread, Thread.CurrentThread.ManagedThreadId, "called on the calling thread");
                seen.Add(f);
            });
            using (RunResult run = TilePatternEngine.Run(Dome, Remesh(), Level(), new TileOptions(), new RunOptions { Tries = 1 }, progress))
            {
                Assert.IsTrue(SameMesh(stageQuads, run.Quads), "the same quads");
                Assert.AreSame(run.Quads, run.Pattern.QuadMesh);
                CollectionAssert.AreEqual(stagePairs, run.Pattern.Pairs, "the same pattern");
                Assert.AreEqual(stageObjective, run.Pattern.Objective);
                AssertSameTiles(stageTiling, run.Tiling, "one try");
                Assert.AreEqual(stageTiling.Report.Joints.P95Deviation, run.Tiling.Report.Joints.P95Deviation);
                // One try is listed nowhere: the report is the stages' own.
                Assert.IsEmpty(run.Tiling.Report.Tries);
                Assert.AreEqual(-1, run.Tiling.Report.ChosenTry);
                StringAssert.DoesNotContain("\"chosen_try\"", run.Tiling.Report.Json);
                StringAssert.StartsWith("One quad mesh tried", UserMessage.ForTries(run.Tiling.Report).Text);
                // The dome's flanks slope by up to 40 degrees: whole tiles there are counted, as
                // lying level or climbing.
                SequenceReport sequence = run.Tiling.Report.Sequence;
                Assert.Greater(sequence.SlopedTiles, 0);
                Assert.That(sequence.ClimbingTiles, Is.InRange(0, sequence.SlopedTiles));
                StringAssert.Contains("\"climbing_tiles\":" + sequence.ClimbingTiles, run.Tiling.Report.Json.Replace(" ", ""));

                // The whole run's progress, on the calling thread, never going back.
                Assert.Greater(seen.Count, 0);
                Assert.IsTrue(seen.All(f => f >= 0.0 && f <= 1.0), "fractions within 0..1");
                CollectionAssert.IsOrdered(seen, "the run's progress never goes back");

                // The handed-out pattern and quads are live: the tile stage on them gives the tiles again.
                AssertSameTiles(stageTiling, TilePatternEngine.Tiles(run.Pattern, new TileOptions(), Dome), "the run's pattern tiled again");
            }
        }

        [Test]
        public void NullOptionsAreTheCommandLinesRun()
        {
            // Level courses on quads for them and the default tile, as `tilepattern run`.
            var tile = new TileOptions();
            using (RunResult given = TilePatternEngine.Run(Dome, RemeshOptions.ForTile(tile, Courses.Level), Level(), tile, new RunOptions { Tries = 1 }))
            using (RunResult defaults = TilePatternEngine.Run(Dome, null, null, null, new RunOptions { Tries = 1 }))
            {
                Assert.IsTrue(SameMesh(given.Quads, defaults.Quads), "the same quads");
                AssertSameTiles(given.Tiling, defaults.Tiling, "null options");
            }
        }

        [Test]
        public void ThreeTriesAreListedAndOneIsKept()
        {
            StagesOneByOne();
            using (RunResult run = TilePatternEngine.Run(Dome, Remesh(), Level(), null, new RunOptions { Tries = 3 }))
            {
                Report report = run.Tiling.Report;
                // The JSON as the library wrote it.
                var root = (Dictionary<string, object>)JsonReader.Parse(report.Json);
                Assert.IsTrue(root.ContainsKey("tries"), "the report lists the tries");
                var tries = (List<object>)root["tries"];
                Assert.AreEqual(3, tries.Count);
                CollectionAssert.AreEqual(new[] { 0.5, 0.5, 1.0 }, tries.Select(t => (double)((Dictionary<string, object>)t)["renormalisation"]).ToArray(),
                    "the default strength, the smooth field at it, twice the strength");
                Assert.IsTrue(root.ContainsKey("chosen_try"));
                int chosen = (int)(double)root["chosen_try"];
                Assert.That(chosen, Is.InRange(0, 2));

                // The same, typed.
                Assert.AreEqual(3, report.Tries.Length);
                Assert.AreEqual(chosen, report.ChosenTry);
                for (int k = 0; k < 3; k++)
                {
                    var json = (Dictionary<string, object>)tries[k];
                    TryReport t = report.Tries[k];
                    Assert.AreEqual((double)json["renormalisation"], t.Renormalisation);
                    Assert.AreEqual(k == 1 ? "smooth" : "curvature", (string)json["field"]);
                    Assert.AreEqual((string)json["field"], t.Field);
                    Assert.AreEqual((int)(double)json["quads"], t.Quads);
                    Assert.AreEqual((double)json["p95_deviation"], t.P95Deviation);
                    Assert.AreEqual((double)json["cut_share"], t.CutShare);
                    Assert.AreEqual((bool)json["wide_joints"], t.WideJoints);
                    Assert.AreEqual((bool)json["fit_cuts"], t.FitCuts);
                    Assert.IsFalse(t.BoundaryFree, "the dome's round rim is followed by no try");
                    Assert.IsNull(t.Failed);
                    Assert.Greater(t.Quads, 100);
                    Assert.That(t.Coverage, Is.InRange(0.5, 1.0 + 1e-9));
                    Assert.That(t.Seconds, Is.GreaterThanOrEqualTo(0.0));
                }
                // The kept try's figures are the tiles'.
                Assert.AreEqual(report.Tries[chosen].P95Deviation, report.Joints.P95Deviation);
                Assert.AreEqual(report.Tries[chosen].Quads, run.Quads.FaceCount);
                // The first try is what one try gives: its quads are handed out exactly when it was kept.
                Assert.AreEqual(chosen == 0, SameMesh(stageQuads, run.Quads));
                Assert.AreEqual(stageTiling.Report.Joints.P95Deviation, report.Tries[0].P95Deviation, "try 1 is the stages' one try");

                string remark = UserMessage.ForTries(report).Text;
                Console.WriteLine("run: " + remark);
                StringAssert.StartsWith("3 tries: the tiles of try " + (chosen + 1) + (chosen == 1 ? " (smooth field, renormalisation " : " (renormalisation "), remark);
                StringAssert.Contains(") are kept: p95 |gap - joint| ", remark);
                Assert.AreEqual(MessageLevel.Remark, UserMessage.ForTries(report).Level);
            }
        }

        [Test]
        public void TheTokenCancelsTheRun()
        {
            using (var cts = new CancellationTokenSource())
            {
                var seen = new List<double>();
                var progress = new SyncProgress(f =>
                {
                    seen.Add(f);
                    if (seen.Count == 3)
                        cts.Cancel();
                });
                var e = Assert.Throws<TilePatternCanceledException>(() =>
                    TilePatternEngine.Run(Dome, Remesh(), Level(), null, new RunOptions { Tries = 3 }, progress, cts.Token));
                Assert.AreEqual(cts.Token, e.CancellationToken);
                Assert.AreEqual(TilePatternStatus.Cancelled, e.Status);
                StringAssert.Contains("cancel", e.NativeMessage);
                Assert.AreEqual(3, seen.Count, "no progress after the cancel");
                Assert.Less(seen[2], 1.0 / 3, "cancelled within the first try");
            }
            using (var late = new CancellationTokenSource())
            {
                // Cancelled in the last try's fit: the run is cancelled, not an earlier try kept.
                var seen = new List<double>();
                var progress = new SyncProgress(f =>
                {
                    seen.Add(f);
                    if (f >= 0.999)
                        late.Cancel();
                });
                Assert.Throws<TilePatternCanceledException>(() =>
                    TilePatternEngine.Run(Dome, Remesh(), Level(), null, new RunOptions { Tries = 3 }, progress, late.Token));
                Assert.GreaterOrEqual(seen[seen.Count - 1], 0.999, "cancelled at the end of the last try");
            }
            using (var cancelled = new CancellationTokenSource())
            {
                cancelled.Cancel();
                var e = Assert.Throws<TilePatternCanceledException>(() => TilePatternEngine.Run(Dome, Remesh(), Level(), null, null, null, cancelled.Token));
                Assert.AreEqual(cancelled.Token, e.CancellationToken);
                StringAssert.Contains("before the call", e.Message);
            }
        }

        [Test]
        public void ARunGoesThroughTheBackgroundJobsAsTheComponentsUseThem()
        {
            // Tile Surface's way: the run on a worker, read on the next pass; cancelled on request.
            var finished = new SemaphoreSlim(0);
            using (var jobs = new BackgroundJobs<RunResult>(() => finished.Release()))
            {
                int caller = Thread.CurrentThread.ManagedThreadId, worker = caller;
                jobs.BeginPass();
                JobStatus<RunResult> started = jobs.Request(0, "one try", (token, progress) =>
                {
                    worker = Thread.CurrentThread.ManagedThreadId;
                    return TilePatternEngine.Run(Dome, Remesh(), Level(), null, new RunOptions { Tries = 1 }, progress, token);
                });
                jobs.EndPass();
                Assert.AreEqual(JobState.Running, started.State);
                Assert.IsTrue(finished.Wait(60000), "the job ended and said so");
                jobs.BeginPass();
                JobStatus<RunResult> done = jobs.Request(0, "one try", (t, p) => null);
                jobs.EndPass();
                Assert.AreEqual(JobState.Done, done.State, done.Error == null ? "" : done.Error.ToString());
                Assert.AreNotEqual(caller, worker, "solved off the calling thread");
                using (RunResult run = done.Result)
                {
                    TileOutputs<string> outputs = TileOutputs<string>.Build(run.Tiling, (tile, pieces) => tile.Label);
                    Assert.AreEqual(run.Tiling.Tiles.Length, outputs.Count);
                    Assert.IsEmpty(outputs.Warnings);
                }

                // Cancel solve while the tries run (here from the run's own progress).
                jobs.BeginPass();
                jobs.Request(0, "three tries", (token, progress) => TilePatternEngine.Run(Dome, Remesh(), Level(), null, new RunOptions { Tries = 3 },
                    new SyncProgress(f =>
                    {
                        progress.Report(f);
                        jobs.CancelAll();
                    }), token));
                jobs.EndPass();
                Assert.IsTrue(finished.Wait(60000));
                jobs.BeginPass();
                JobStatus<RunResult> cancelled = jobs.Request(0, "three tries", (t, p) => null);
                jobs.EndPass();
                Assert.AreEqual(JobState.Cancelled, cancelled.State);
                Assert.IsNull(cancelled.Result);
                Assert.AreEqual("Cancelled", jobs.Summary);
            }
        }

        [Test]
        public void TriesOutsideZeroToMaxTriesAreRefusedByName()
        {
            Assert.AreEqual(0, new RunOptions().Tries, "automatic by default");
            foreach (int tries in new[] { RunOptions.MaxTries + 1, -1 })
            {
                var e = Assert.Throws<ArgumentOutOfRangeException>(() => TilePatternEngine.Run(Dome, Remesh(), Level(), null, new RunOptions { Tries = tries }),
                    "Tries = " + tries);
                Assert.AreEqual("Tries", e.ParamName);
                StringAssert.Contains("Tries is 0 (automatic", e.Message);
                StringAssert.Contains("not " + tries, e.Message);
            }
        }

        [Test]
        public void QuadsNamedBeforeTheyExistAreRefused()
        {
            var forced = Level();
            forced.ForcedPairs.Add(new FacePair(0, 1));
            var e = Assert.Throws<ArgumentException>(() => TilePatternEngine.Run(Dome, Remesh(), forced, null, new RunOptions { Tries = 1 }));
            Assert.AreEqual("pattern", e.ParamName);
            StringAssert.Contains("ForcedPairs must be empty for Run (it lists 1)", e.Message);
            StringAssert.Contains("call Remesh, Match and Tiles one by one", e.Message);

            Assert.Throws<ArgumentNullException>(() => TilePatternEngine.Run(null));
        }

        [Test]
        public void ExcludedFacesAreFacesOfTheSurfaceAndAreNotTiled()
        {
            StagesOneByOne();
            // The quarter of the dome where x and y > 0, by its faces' centroids.
            var excluded = Level();
            double[] v = Dome.Vertices;
            int[] idx = Dome.FaceIndices, sizes = Dome.FaceSizes;
            for (int f = 0, at = 0; f < sizes.Length; at += sizes[f], f++)
            {
                double x = 0.0, y = 0.0;
                for (int k = 0; k < sizes[f]; k++)
                {
                    x += v[3 * idx[at + k]] / sizes[f];
                    y += v[3 * idx[at + k] + 1] / sizes[f];
                }
                if (x > 0.0 && y > 0.0)
                    excluded.ExcludedFaces.Add(f);
            }
            using (RunResult run = TilePatternEngine.Run(Dome, Remesh(), excluded, null, new RunOptions { Tries = 1 }))
            {
                Tile[] tiles = run.Tiling.Tiles;
                int all = stageTiling.Tiles.Length;
                Assert.That(tiles.Length, Is.InRange(all / 2, all * 85 / 100), "about a quarter fewer tiles");
                foreach (Tile t in tiles)
                {
                    double x = 0.0, y = 0.0;
                    for (int c = 0; c < 8; c++)
                    {
                        x += t.Corners[3 * c] / 8.0;
                        y += t.Corners[3 * c + 1] / 8.0;
                    }
                    Assert.IsFalse(x > 0.3 && y > 0.3, "tile " + t.Index + " lies inside the faces left out");
                }
            }
            var beyond = Level();
            beyond.ExcludedFaces.Add(Dome.FaceCount);
            var e = Assert.Throws<InvalidArgumentException>(() => TilePatternEngine.Run(Dome, Remesh(), beyond, null, new RunOptions { Tries = 1 }));
            StringAssert.Contains("face " + Dome.FaceCount, e.Message);
        }

        [Test]
        public void ZonesArePerSurfaceFace()
        {
            StagesOneByOne();
            // One zone per quad is not one per surface face: refused before the remesh.
            var perQuad = Level();
            perQuad.Zones = new Bond?[stageQuads.FaceCount];
            var e = Assert.Throws<InvalidArgumentException>(() => TilePatternEngine.Run(Dome, Remesh(), perQuad, null, new RunOptions { Tries = 1 }));
            StringAssert.Contains("for a mesh of " + Dome.FaceCount + " faces", e.Message);
            // Every surface face in the default bond: the tiles without zones.
            var perFace = Level();
            perFace.Zones = new Bond?[Dome.FaceCount];
            using (RunResult run = TilePatternEngine.Run(Dome, Remesh(), perFace, null, new RunOptions { Tries = 1 }))
                AssertSameTiles(stageTiling, run.Tiling, "null zones");
        }

        [Test]
        public void TheTriesRemarkNamesTheKeptTryAndEveryOther()
        {
            const string json = @"{""faces"": 10, ""warnings"": [], ""tries"": [
                {""renormalisation"": 0.5, ""quads"": 300, ""interior_irregular_vertices"": 4, ""p95_deviation"": 0.0042, ""cut_share"": 0.021, ""coverage"": 0.98, ""wide_joints"": false, ""score"": 3.0, ""seconds"": 1.5},
                {""renormalisation"": 1, ""quads"": 296, ""interior_irregular_vertices"": 2, ""p95_deviation"": 0.0031, ""cut_share"": 0.012, ""coverage"": 0.99, ""wide_joints"": false, ""score"": 2.0, ""seconds"": 1.4},
                {""renormalisation"": 0.25, ""quads"": 310, ""interior_irregular_vertices"": 6, ""p95_deviation"": 0.0061, ""cut_share"": 0.0, ""coverage"": 0.98, ""wide_joints"": true, ""score"": 1.0, ""seconds"": 10.2, ""limit_reached"": ""pattern"", ""ended_tries"": true}],
                ""chosen_try"": 1}";
            Report report = Report.Parse(json);
            Assert.AreEqual(3, report.Tries.Length);
            Assert.AreEqual(1, report.ChosenTry);
            Assert.AreEqual(0.0031, report.Tries[1].P95Deviation);
            Assert.AreEqual(2, report.Tries[1].InteriorIrregularVertices);
            Assert.AreEqual(1.4, report.Tries[1].Seconds);
            Assert.AreEqual(2.0, report.Tries[1].Score);
            Assert.IsTrue(report.Tries[2].WideJoints);
            Assert.AreEqual("pattern", report.Tries[2].LimitReached);
            Assert.IsNull(report.Tries[0].LimitReached);
            UserMessage remark = UserMessage.ForTries(report);
            Assert.AreEqual(MessageLevel.Remark, remark.Level);
            Assert.AreEqual("3 tries: the tiles of try 2 (renormalisation 1) are kept: p95 |gap - joint| 0.0031, 1.2 % of tiles cut, coverage 0.99, score 2."
                + " Try 1 (renormalisation 0.5): p95 |gap - joint| 0.0042, 2.1 % of tiles cut, coverage 0.98, score 3;"
                + " try 3 (renormalisation 0.25): p95 |gap - joint| 0.0061 (wide joints), 0 % of tiles cut, coverage 0.98, score 1,"
                + " its pattern stage reached its time limit, so no further try was made and it is not kept.",
                remark.Text);
            // The first try's pattern stage reaching its limit does not end the tries.
            const string first = @"{""faces"": 10, ""warnings"": [], ""tries"": [
                {""renormalisation"": 0.5, ""quads"": 300, ""interior_irregular_vertices"": 40, ""p95_deviation"": 0.0092, ""cut_share"": 0.3, ""coverage"": 0.96, ""wide_joints"": true, ""score"": 40.0, ""seconds"": 70.5, ""limit_reached"": ""pattern""},
                {""renormalisation"": 0.5, ""field"": ""smooth"", ""quads"": 296, ""interior_irregular_vertices"": 20, ""p95_deviation"": 0.0082, ""cut_share"": 0.17, ""coverage"": 0.97, ""wide_joints"": true, ""score"": 21.5, ""seconds"": 5.3}],
                ""chosen_try"": 1}";
            Report firstLimited = Report.Parse(first);
            Assert.IsFalse(firstLimited.Tries[0].EndedTries);
            Assert.IsTrue(report.Tries[2].EndedTries);
            StringAssert.EndsWith("its pattern stage reached its time limit, so its tiles depend on the machine's speed and it is not kept.",
                UserMessage.ForTries(firstLimited).Text);
            // A report written before tries named their field reads as the curvature's; the
            // smooth try is named in the remark.
            Assert.AreEqual("curvature", report.Tries[0].Field);
            Report smooth = Report.Parse(@"{""faces"": 10, ""warnings"": [], ""tries"": [
                {""renormalisation"": 0.5, ""field"": ""curvature"", ""quads"": 300, ""interior_irregular_vertices"": 4, ""p95_deviation"": 0.0042, ""cut_share"": 0.021, ""coverage"": 0.98, ""wide_joints"": false, ""score"": 3.0, ""seconds"": 1.5},
                {""renormalisation"": 0.5, ""field"": ""smooth"", ""quads"": 296, ""interior_irregular_vertices"": 0, ""p95_deviation"": 0.0031, ""cut_share"": 0.012, ""coverage"": 0.99, ""wide_joints"": false, ""score"": 2.0, ""seconds"": 1.4}],
                ""chosen_try"": 1}");
            Assert.AreEqual("smooth", smooth.Tries[1].Field);
            StringAssert.StartsWith("2 tries: the tiles of try 2 (smooth field, renormalisation 0.5) are kept", UserMessage.ForTries(smooth).Text);
            StringAssert.Contains("Try 1 (renormalisation 0.5): ", UserMessage.ForTries(smooth).Text);
            // A report of the stages one by one has no tries.
            Report plain = Report.Parse(@"{""faces"": 10, ""warnings"": []}");
            Assert.IsEmpty(plain.Tries);
            Assert.AreEqual(-1, plain.ChosenTry);
        }
    }
}

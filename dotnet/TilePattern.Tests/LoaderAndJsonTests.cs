// The native library resolver's search list, and the report's JSON reader.
using System;
using System.Collections.Generic;
using System.IO;
using NUnit.Framework;

namespace TilePattern.Tests
{
    [TestFixture]
    public class LoaderTests
    {
        [Test]
        public void LoadedFromTheEnvironmentVariable()
        {
            string env = Environment.GetEnvironmentVariable("TILEPATTERN_LIB");
            if (string.IsNullOrEmpty(env))
                Assert.Ignore("TILEPATTERN_LIB is not set (scripts/test-dotnet.sh sets it)");
            Assert.AreEqual(Path.GetFullPath(env), TilePatternEngine.NativeLibraryPath, TilePatternEngine.NativeLibraryDescription);
            if (NativeLibraryLoader.IsMono)
                StringAssert.Contains("mono dllmap", TilePatternEngine.NativeLibraryDescription);
        }

        [Test]
        public void SearchOrder()
        {
            string file = NativeLibraryLoader.FileName;
            string baseDir = Path.Combine(Path.GetTempPath(), "tp-loader-test");
            List<string> list = NativeLibraryLoader.Candidates(Path.Combine("x", "my.so"), baseDir);
            Assert.AreEqual(Path.Combine("x", "my.so"), list[0], "the override comes first");
            string rid = NativeLibraryLoader.RuntimeIdentifiers()[0];
            Assert.AreEqual(Path.Combine(baseDir, "runtimes", rid, "native", file), list[1]);
            Assert.AreEqual(Path.Combine(baseDir, file), list[list.Count - 1], "next to the assembly last");
            if (NativeLibraryLoader.IsWindows)
                Assert.AreEqual("tilepattern.dll", file);
            else if (NativeLibraryLoader.IsMacOS)
                Assert.AreEqual("libtilepattern.dylib", file);
            else
            {
                Assert.AreEqual("libtilepattern.so", file);
                StringAssert.StartsWith("linux-", rid);
            }
            // An override naming a folder means the file in it, then the runtimes layout under it.
            List<string> folder = NativeLibraryLoader.Candidates(Path.GetTempPath(), null);
            Assert.AreEqual(Path.Combine(Path.GetTempPath(), file), folder[0]);
            Assert.AreEqual(Path.Combine(Path.GetTempPath(), "runtimes", rid, "native", file), folder[1]);
            Assert.AreEqual(0, NativeLibraryLoader.Candidates(null, null).Count);
        }

        [Test]
        public void OverrideAfterLoadingHasNoEffect()
        {
            Assert.IsNotNull(TilePatternEngine.NativeVersion);
            Assert.IsFalse(TilePatternEngine.UseNativeLibrary("/nonexistent/libtilepattern.so"));
        }
    }

    [TestFixture]
    public class JsonTests
    {
        [Test]
        public void ReadsValues()
        {
            var o = (Dictionary<string, object>)JsonReader.Parse(
                "{ \"a\": 1.5e2, \"b\": [true, false, null, -0.25], \"c\": {\"d\": \"x\\\"y\\\\z\\u00e9\\n\"}, \"e\": [], \"f\": {} }");
            Assert.AreEqual(150.0, o["a"]);
            CollectionAssert.AreEqual(new object[] { true, false, null, -0.25 }, (List<object>)o["b"]);
            Assert.AreEqual("x\"y\\z\u00e9\n", ((Dictionary<string, object>)o["c"])["d"]);
            Assert.IsEmpty((List<object>)o["e"]);
            Assert.IsEmpty((Dictionary<string, object>)o["f"]);
        }

        [Test]
        public void RejectsMalformedText()
        {
            foreach (string bad in new[] { "", "{", "{\"a\" 1}", "[1,]", "{\"a\": 1} x", "\"open", "tru", "{\"a\": 1,}", "[1 2]" })
                Assert.Throws<FormatException>(() => JsonReader.Parse(bad), bad);
            Assert.Throws<ArgumentNullException>(() => JsonReader.Parse(null));
        }

        [Test]
        public void ReportFromJson()
        {
            Report r = Report.Parse("{\"faces\": 4, \"full_tiles\": 2, \"half_tiles\": 0, \"non_quad_faces\": 0, \"excluded_faces\": 0,"
                + "\"continuous_joints\": 1, \"shifted_pairs\": 0, \"objective\": 1.5, \"bound\": 2.0, \"gap\": 0.25, \"status\": \"time_limit\","
                + "\"tile\": {\"length\": 0.28, \"width\": 0.14, \"thickness\": 0.015, \"joint\": 0.01},"
                + "\"joints\": {\"contacts\": 3, \"joint\": 0.01, \"min_gap\": -0.001, \"max_gap\": 0.02, \"mean_gap\": 0.011, \"p95_deviation\": 0.004, \"overlaps\": 1},"
                + "\"seconds\": {\"pattern\": 0.5, \"tiles\": 0.01}, \"something_new\": [1, 2]}");
            Assert.AreEqual(4, r.Faces);
            Assert.AreEqual(2, r.FullTiles);
            Assert.AreEqual(1, r.ContinuousJoints);
            Assert.AreEqual(SolveStatus.TimeLimit, r.Status);
            Assert.AreEqual("time_limit", r.StatusText);
            Assert.AreEqual(0.28, r.Tile.Length);
            Assert.AreEqual(-0.001, r.Joints.MinGap);
            Assert.AreEqual(1, r.Joints.Overlaps);
            Assert.AreEqual(0.5, r.PatternSeconds);
            Assert.AreEqual(0.01, r.TileSeconds);
            Assert.Throws<FormatException>(() => Report.Parse("[1]"));
        }

        [Test]
        public void AWarningGivesTheFaceItNames()
        {
            Report r = Report.Parse("{\"faces\": 4, \"warnings\": ["
                + "{\"code\": \"folded_surface\", \"message\": \"... at face 12 near ...\", \"face\": 12},"
                + "{\"code\": \"low_coverage\", \"message\": \"the tiles cover 0.5\"}]}");
            Assert.AreEqual(TilingWarningCode.FoldedSurface, r.Warnings[0].Code);
            Assert.AreEqual(12, r.Warnings[0].Face);
            Assert.AreEqual(-1, r.Warnings[1].Face);
        }

        [Test]
        public void EachTryNamesItsQuadMeshAndItsFlags()
        {
            Report r = Report.Parse("{\"faces\": 4, \"chosen_try\": 1, \"tries\": ["
                + "{\"renormalisation\": 0.5, \"field\": \"curvature\", \"quads\": 4, \"p95_deviation\": 0.002, \"cut_share\": 0.02,"
                + " \"coverage\": 0.99, \"wide_joints\": false, \"fit_cuts\": true, \"score\": 3.4, \"seconds\": 0.1},"
                + "{\"renormalisation\": 0.5, \"field\": \"smooth\", \"boundary_free\": true, \"quads\": 4, \"p95_deviation\": 0.003,"
                + " \"cut_share\": 0.0, \"coverage\": 0.99, \"wide_joints\": false, \"fit_cuts\": false, \"score\": 1.6, \"seconds\": 0.1}]}");
            Assert.AreEqual(2, r.Tries.Length);
            Assert.IsTrue(r.Tries[0].FitCuts);
            Assert.IsFalse(r.Tries[0].BoundaryFree);
            Assert.IsFalse(r.Tries[1].FitCuts);
            Assert.IsTrue(r.Tries[1].BoundaryFree);
            Assert.IsFalse(r.Tries[1].QuadsAlongCourses);
            string remark = UserMessage.ForTries(r).Text;
            StringAssert.Contains("try 2 (smooth field, boundary free, renormalisation 0.5) are kept", remark);
            StringAssert.Contains("2 % of tiles cut (over 1 %)", remark);
        }
    }
}

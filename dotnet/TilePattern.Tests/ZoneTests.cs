// Zones (issue 20): PatternOptions.Zones, a bond per face, reaches the library; bad zones are
// refused with the face or the count at fault.
using System;
using System.Linq;
using NUnit.Framework;

namespace TilePattern.Tests
{
    [TestFixture]
    public class ZoneTests
    {
        /// <summary>Zones of an 8 x 8 grid: rows 3 and 4 in <paramref name="bond"/>, the rest null.</summary>
        static Bond?[] Band(Bond bond)
        {
            return Enumerable.Range(0, 64).Select(f => f / 8 == 3 || f / 8 == 4 ? (Bond?)bond : null).ToArray();
        }

        [Test]
        public void NullZonesGiveTheOptimumWithoutZones()
        {
            PolyMesh grid = TestMeshes.Grid(8, 8);
            Assert.IsNull(new PatternOptions().Zones);
            using (Pattern plain = TilePatternEngine.Match(grid, new PatternOptions { Courses = Courses.Free, TimeLimitSeconds = 10 }))
            using (Pattern zoned = TilePatternEngine.Match(grid, new PatternOptions { Courses = Courses.Free, TimeLimitSeconds = 10, Zones = new Bond?[64] }))
            {
                // Both proven: the same optimum (the patterns may differ among equal optima).
                Assert.AreEqual(SolveStatus.Optimal, plain.Status);
                Assert.AreEqual(SolveStatus.Optimal, zoned.Status);
                Assert.AreEqual(plain.Objective, zoned.Objective);
            }
        }

        [Test]
        public void AHerringboneBandReachesTheSolve()
        {
            PolyMesh grid = TestMeshes.Grid(8, 8);
            // Level courses refuse a herringbone zone (the bond itself is staggered): the zones
            // reach the options.
            var level = Assert.Throws<InvalidArgumentException>(() =>
                TilePatternEngine.Match(grid, new PatternOptions { Courses = Courses.Level, Zones = Band(Bond.Herringbone) }));
            StringAssert.Contains("herringbone", level.Message);
            StringAssert.Contains("courses free", level.Message);
            using (Pattern pattern = TilePatternEngine.Match(grid, new PatternOptions { Courses = Courses.Free, TimeLimitSeconds = 10, Zones = Band(Bond.Herringbone) }))
            {
                Assert.Greater(pattern.Pairs.Length, 0);
                Assert.GreaterOrEqual(pattern.Bound, pattern.Objective);
                Assert.IsTrue(pattern.Pairs.All(p => (p.B == p.A + 1 && p.A % 8 != 7) || p.B == p.A + 8));
            }
        }

        [Test]
        public void BadZonesNameTheFaceOrTheCount()
        {
            PolyMesh grid = TestMeshes.Grid(4, 4);
            var count = Assert.Throws<InvalidArgumentException>(() =>
                TilePatternEngine.Match(grid, new PatternOptions { Courses = Courses.Free, Zones = new Bond?[15] }));
            StringAssert.Contains("15 bonds for a mesh of 16 faces", count.Message);
            var zones = new Bond?[16];
            zones[3] = (Bond)9;
            var code = Assert.Throws<InvalidArgumentException>(() =>
                TilePatternEngine.Match(grid, new PatternOptions { Courses = Courses.Free, Zones = zones }));
            StringAssert.Contains("zones[3] is 9", code.Message);
            Assert.Throws<ArgumentException>(() =>
                TilePatternEngine.Match(grid, new PatternOptions { Courses = Courses.Free, Zones = new Bond?[0] }));
        }
    }
}

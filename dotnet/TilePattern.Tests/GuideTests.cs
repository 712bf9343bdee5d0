// Guide curves (issue 20): RemeshOptions.Guides (polylines) and GuideWeight reach the
// library; bad curves are refused with the curve and point at fault.
using System;
using NUnit.Framework;

namespace TilePattern.Tests
{
    [TestFixture]
    public class GuideTests
    {
        const double Angle = 30.0 * Math.PI / 180.0;

        static PolyMesh Plate()
        {
            return TestMeshes.CurvedTriangles(24, 1.74, 0.0);
        }

        /// <summary>A line through the plate's centre at 30 degrees, in three points, and a
        /// short one near a corner along the same direction.</summary>
        static double[][][] Guides()
        {
            double c = Math.Cos(Angle), s = Math.Sin(Angle);
            return new[]
            {
                new[] { new[] { -0.9 * c, -0.9 * s, 0.0 }, new[] { 0.0, 0.0, 0.0 }, new[] { 0.9 * c, 0.9 * s, 0.0 } },
                new[] { new[] { -0.8, -0.8, 0.0 }, new[] { -0.8 + 0.3 * c, -0.8 + 0.3 * s, 0.0 } },
            };
        }

        /// <summary>Mean |cos 4 theta| of the edges against the guides' direction: 1 when every
        /// edge is on it or across it.</summary>
        static double Alignment(PolyMesh quads)
        {
            double[] v = quads.Vertices;
            double sum = 0;
            int count = 0;
            foreach (int[] face in quads.Faces())
                for (int k = 0; k < face.Length; k++)
                {
                    int a = face[k], b = face[(k + 1) % face.Length];
                    double theta = Math.Atan2(v[3 * b + 1] - v[3 * a + 1], v[3 * b] - v[3 * a]) - Angle;
                    sum += Math.Abs(Math.Cos(4 * theta));
                    count++;
                }
            return sum / count;
        }

        [Test]
        public void GuidesTurnTheQuads()
        {
            PolyMesh plate = Plate();
            double plain = Alignment(TilePatternEngine.Remesh(plate, new RemeshOptions()));
            var guided = new RemeshOptions { Guides = Guides() };
            Assert.AreEqual(1.0, guided.GuideWeight, "the library's default weight");
            double turned = Alignment(TilePatternEngine.Remesh(plate, guided));
            double again = Alignment(TilePatternEngine.Remesh(plate, guided));
            double none = Alignment(TilePatternEngine.Remesh(plate, new RemeshOptions { Guides = Guides(), GuideWeight = 0.0 }));
            Console.WriteLine("guides: alignment {0:F3} without, {1:F3} with, {2:F3} at weight 0", plain, turned, none);
            Assert.Greater(turned, plain + 0.2, "guided");
            Assert.AreEqual(turned, again, "deterministic");
            Assert.Less(none, turned - 0.2, "weight 0");
        }

        [Test]
        public void BadGuidesNameTheCurveAtFault()
        {
            PolyMesh plate = Plate();
            double[][][] guides = Guides();
            guides[1] = new[] { new[] { 0.0, 0.0, 0.0 } };
            var e = Assert.Throws<InvalidArgumentException>(() => TilePatternEngine.Remesh(plate, new RemeshOptions { Guides = guides }));
            StringAssert.Contains("guide curve 1 has 1 point", e.Message);
            guides = Guides();
            guides[0][2] = new[] { double.NaN, 0.0, 0.0 };
            e = Assert.Throws<InvalidArgumentException>(() => TilePatternEngine.Remesh(plate, new RemeshOptions { Guides = guides }));
            StringAssert.Contains("point 2 of guide curve 0", e.Message);
            guides = Guides();
            guides[1] = new[] { new[] { 0.0, 0.0, 3.0 }, new[] { 1.0, 0.0, 3.0 } };
            e = Assert.Throws<InvalidArgumentException>(() => TilePatternEngine.Remesh(plate, new RemeshOptions { Guides = guides }));
            StringAssert.Contains("guide curve 1 is nowhere near", e.Message);
            e = Assert.Throws<InvalidArgumentException>(() => TilePatternEngine.Remesh(plate, new RemeshOptions { Guides = Guides(), GuideWeight = 1.5 }));
            StringAssert.Contains("guide weight", e.Message);
            guides = Guides();
            guides[0][1] = new[] { 1.0, 0.0 };
            var a = Assert.Throws<ArgumentException>(() => TilePatternEngine.Remesh(plate, new RemeshOptions { Guides = guides }));
            StringAssert.Contains("Guides[0][1]", a.Message);
        }
    }
}

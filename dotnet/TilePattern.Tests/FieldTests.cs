// The designer's field (issue 20): RemeshOptions.Field (one vector per vertex or per face)
// and FieldWeight reach the library; bad fields are refused with the index at fault.
using System;
using NUnit.Framework;

namespace TilePattern.Tests
{
    [TestFixture]
    public class FieldTests
    {
        const double Angle = 30.0 * Math.PI / 180.0;

        static PolyMesh Plate()
        {
            return TestMeshes.CurvedTriangles(24, 1.74, 0.0);
        }

        static double[][] Vectors(int count, bool scramble)
        {
            var field = new double[count][];
            for (int i = 0; i < count; i++)
            {
                double s = scramble && i % 2 == 1 ? -3.0 : 1.0;
                field[i] = new[] { s * Math.Cos(Angle), s * Math.Sin(Angle), 0.0 };
            }
            return field;
        }

        /// <summary>Mean |cos 4 theta| of the edges against the field's direction: 1 when
        /// every edge is on it or across it.</summary>
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
        public void AFieldPerFaceOrPerVertexTurnsTheQuads()
        {
            PolyMesh plate = Plate();
            double plain = Alignment(TilePatternEngine.Remesh(plate, new RemeshOptions()));
            var byFace = new RemeshOptions { Field = Vectors(plate.FaceCount, true) };
            Assert.AreEqual(1.0, byFace.FieldWeight, "the library's default weight");
            double turned = Alignment(TilePatternEngine.Remesh(plate, byFace));
            double byVertex = Alignment(TilePatternEngine.Remesh(plate, new RemeshOptions { Field = Vectors(plate.VertexCount, false) }));
            double none = Alignment(TilePatternEngine.Remesh(plate, new RemeshOptions { Field = Vectors(plate.FaceCount, true), FieldWeight = 0.0 }));
            Assert.Greater(turned, plain + 0.2, "per face");
            Assert.Greater(byVertex, plain + 0.2, "per vertex");
            Assert.Less(none, turned - 0.2, "weight 0");
        }

        [Test]
        public void BadFieldsNameTheIndexAtFault()
        {
            PolyMesh plate = Plate();
            double[][] field = Vectors(plate.FaceCount, false);
            field[7] = new[] { 0.0, 0.0, 0.0 };
            var e = Assert.Throws<InvalidArgumentException>(() => TilePatternEngine.Remesh(plate, new RemeshOptions { Field = field }));
            StringAssert.Contains("face 7", e.Message);
            field[7] = new[] { double.NaN, 1.0, 0.0 };
            e = Assert.Throws<InvalidArgumentException>(() => TilePatternEngine.Remesh(plate, new RemeshOptions { Field = field }));
            StringAssert.Contains("face 7", e.Message);
            e = Assert.Throws<InvalidArgumentException>(() => TilePatternEngine.Remesh(plate, new RemeshOptions { Field = Vectors(5, false) }));
            StringAssert.Contains("5 vectors", e.Message);
            e = Assert.Throws<InvalidArgumentException>(() =>
                TilePatternEngine.Remesh(plate, new RemeshOptions { Field = Vectors(plate.VertexCount, false), FieldWeight = 1.5 }));
            StringAssert.Contains("weight", e.Message);
            field[7] = new[] { 1.0, 0.0 };
            var a = Assert.Throws<ArgumentException>(() => TilePatternEngine.Remesh(plate, new RemeshOptions { Field = field }));
            StringAssert.Contains("Field[7]", a.Message);
        }
    }
}

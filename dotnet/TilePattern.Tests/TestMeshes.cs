// Meshes built in C# for the tests.
using System;
using System.Collections.Generic;

namespace TilePattern.Tests
{
    internal static class TestMeshes
    {
        /// <summary>An nx x ny grid of square quads of side <paramref name="size"/> in the xy plane.</summary>
        public static PolyMesh Grid(int nx, int ny, double size = 1.0)
        {
            var v = new List<double>();
            for (int j = 0; j <= ny; j++)
                for (int i = 0; i <= nx; i++)
                {
                    v.Add(i * size);
                    v.Add(j * size);
                    v.Add(0.0);
                }
            var faces = new List<int[]>();
            for (int j = 0; j < ny; j++)
                for (int i = 0; i < nx; i++)
                {
                    int a = i + (nx + 1) * j;
                    faces.Add(new[] { a, a + 1, a + nx + 2, a + nx + 1 });
                }
            return PolyMesh.FromFaces(v.ToArray(), faces);
        }

        /// <summary>A doubly curved shell patch, side <paramref name="span"/> (metres), as
        /// 2 n^2 triangles: z = rise * (1 - (2x/span)^2) * (1 - (2y/span)^2) / ... a dome-like cap.</summary>
        public static PolyMesh CurvedTriangles(int n, double span, double rise)
        {
            var v = new List<double>();
            for (int j = 0; j <= n; j++)
                for (int i = 0; i <= n; i++)
                {
                    double x = span * i / n - span / 2, y = span * j / n - span / 2;
                    double u = 2 * x / span, w = 2 * y / span;
                    v.Add(x);
                    v.Add(y);
                    v.Add(rise * (1 - 0.5 * u * u) * (1 - 0.5 * w * w));
                }
            var faces = new List<int[]>();
            for (int j = 0; j < n; j++)
                for (int i = 0; i < n; i++)
                {
                    int a = i + (n + 1) * j, b = a + 1, c = a + n + 2, d = a + n + 1;
                    faces.Add(new[] { a, b, c });
                    faces.Add(new[] { a, c, d });
                }
            return PolyMesh.FromFaces(v.ToArray(), faces);
        }
    }
}

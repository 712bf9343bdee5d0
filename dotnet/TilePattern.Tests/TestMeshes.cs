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
            return Grid(nx, ny, size, (x, y) => 0.0);
        }

        /// <summary>An nx x ny grid of quads of side <paramref name="size"/> (in plan) lifted to
        /// z = height(x, y); faces numbered row by row along x.</summary>
        public static PolyMesh Grid(int nx, int ny, double size, Func<double, double, double> height)
        {
            var v = new List<double>();
            for (int j = 0; j <= ny; j++)
                for (int i = 0; i <= nx; i++)
                {
                    v.Add(i * size);
                    v.Add(j * size);
                    v.Add(height(i * size, j * size));
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

        /// <summary>A closed cube of side 2n, each side n x n unit quads, normals out.</summary>
        public static PolyMesh Cube(int n)
        {
            var v = new List<double>();
            var index = new Dictionary<string, int>();
            var faces = new List<int[]>();
            for (int k = 0; k < 3; k++)
                for (int sign = -1; sign <= 1; sign += 2)
                {
                    int a = (k + 1) % 3, b = (k + 2) % 3;
                    if (sign < 0) { int t = a; a = b; b = t; }
                    var at = new int[n + 1, n + 1];
                    for (int j = 0; j <= n; j++)
                        for (int i = 0; i <= n; i++)
                        {
                            var p = new double[3];
                            p[k] = sign * n;
                            p[a] = 2 * i - n;
                            p[b] = 2 * j - n;
                            string key = p[0] + "," + p[1] + "," + p[2];
                            int found;
                            if (!index.TryGetValue(key, out found))
                            {
                                found = v.Count / 3;
                                index[key] = found;
                                v.AddRange(p);
                            }
                            at[i, j] = found;
                        }
                    for (int j = 0; j < n; j++)
                        for (int i = 0; i < n; i++)
                            faces.Add(new[] { at[i, j], at[i + 1, j], at[i + 1, j + 1], at[i, j + 1] });
                }
            return PolyMesh.FromFaces(v.ToArray(), faces);
        }

        /// <summary>A strongly curved wave of 2 x 1.6 (metres) as triangles, z = 0.8 sin(3x)
        /// sin(4y): tiles of 280 x 140 mm on quads of 145 mm cannot all be fitted to it, so the
        /// fit stage cuts some (13; on the gentler 0.8 sin(2x) sin(3y) the fit, since joints
        /// that cannot close gather into tears, cuts none).</summary>
        public static PolyMesh Wave()
        {
            PolyMesh quads = Grid(40, 32, 0.05, (x, y) => 0.8 * Math.Sin(3 * x) * Math.Sin(4 * y));
            var faces = new List<int[]>();
            for (int f = 0; f < quads.FaceCount; f++)
            {
                int[] q = quads.Face(f);
                faces.Add(new[] { q[0], q[1], q[2] });
                faces.Add(new[] { q[0], q[2], q[3] });
            }
            return PolyMesh.FromFaces(quads.Vertices, faces);
        }

        /// <summary>The C tests' round dome: a spherical cap of radius 2 over a disk of radius 1.3
        /// (metres), as triangles: a centre and 12 rings of 48 vertices (1,104 faces).</summary>
        public static PolyMesh RoundDome()
        {
            const int rings = 12, sectors = 48;
            var v = new List<double> { 0.0, 0.0, 2.0 };
            for (int i = 1; i <= rings; i++)
                for (int j = 0; j < sectors; j++)
                {
                    double r = 1.3 * i / rings, a = 2.0 * Math.PI * j / sectors;
                    v.Add(r * Math.Cos(a));
                    v.Add(r * Math.Sin(a));
                    v.Add(Math.Sqrt(4.0 - r * r));
                }
            Func<int, int, int> id = (i, j) => i == 0 ? 0 : 1 + (i - 1) * sectors + j % sectors;
            var faces = new List<int[]>();
            for (int j = 0; j < sectors; j++)
                faces.Add(new[] { 0, id(1, j), id(1, j + 1) });
            for (int i = 1; i < rings; i++)
                for (int j = 0; j < sectors; j++)
                {
                    int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
                    faces.Add(new[] { a, b, c });
                    faces.Add(new[] { a, c, d });
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

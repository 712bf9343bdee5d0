// PolyMesh.JoinVertices: a mesh whose faces do not share their vertices along seams (a
// polysurface meshed face by face, as Grasshopper hands it over) joined by groups of vertices,
// faces keeping their numbers.
using System;
using System.Collections.Generic;
using System.Linq;
using NUnit.Framework;

namespace TilePattern.Tests
{
    [TestFixture]
    public class JoinTests
    {
        /// <summary><paramref name="mesh"/> with each piece's faces (<paramref name="pieceOf"/>
        /// a face) on vertices of their own, as a polysurface meshed face by face; and each new
        /// vertex's group: the original vertex it copies.</summary>
        static PolyMesh Apart(PolyMesh mesh, Func<int, int> pieceOf, out int[] group)
        {
            var xyz = new List<double>();
            var faces = new List<int[]>();
            var groups = new List<int>();
            var copies = new Dictionary<KeyValuePair<int, int>, int>();
            int[][] all = mesh.Faces();
            for (int f = 0; f < all.Length; f++)
            {
                var own = new int[all[f].Length];
                for (int k = 0; k < own.Length; k++)
                {
                    var key = new KeyValuePair<int, int>(pieceOf(f), all[f][k]);
                    int copy;
                    if (!copies.TryGetValue(key, out copy))
                    {
                        copy = copies[key] = groups.Count;
                        groups.Add(all[f][k]);
                        xyz.AddRange(mesh.Vertex(all[f][k]));
                    }
                    own[k] = copy;
                }
                faces.Add(own);
            }
            group = groups.ToArray();
            return PolyMesh.FromFaces(xyz.ToArray(), faces);
        }

        [Test]
        public void ASoupJoinedByPlaceIsTheMeshItCameFrom()
        {
            PolyMesh grid = TestMeshes.Grid(4, 3);
            int[] group;
            PolyMesh soup = Apart(grid, f => f, out group);
            Assert.AreEqual(48, soup.VertexCount);
            int[] first;
            PolyMesh joined = soup.JoinVertices(group, out first);
            Assert.AreEqual(grid.VertexCount, joined.VertexCount);
            CollectionAssert.AreEqual(grid.Vertices, joined.Vertices);
            CollectionAssert.AreEqual(grid.FaceIndices, joined.FaceIndices);
            CollectionAssert.AreEqual(grid.FaceSizes, joined.FaceSizes);
            // Each joined vertex is its group's first: the soup's first copy of it.
            for (int v = 0; v < first.Length; v++)
                Assert.AreEqual(Array.IndexOf(group, v), first[v]);
            TilePatternEngine.Validate(joined);
        }

        [Test]
        public void APolysurfaceMeshIsTiledAsOneSurfaceOnceJoined()
        {
            // The dome in four quarters, each with its own vertices along the seams.
            PolyMesh dome = TestMeshes.RoundDome();
            int[] group;
            PolyMesh soup = Apart(dome, f =>
            {
                double[] c = dome.FaceCenter(f);
                return (c[0] > 0 ? 2 : 0) + (c[1] > 0 ? 1 : 0);
            }, out group);
            Assert.Greater(soup.VertexCount, dome.VertexCount);
            int[] first;
            PolyMesh joined = soup.JoinVertices(group, out first);
            var pattern = new PatternOptions { Courses = Courses.Level };
            var remesh = RemeshOptions.ForTile(new TileOptions(), Courses.Level);
            using (RunResult apart = TilePatternEngine.Run(soup, remesh, pattern, null, new RunOptions { Tries = 1 }))
            using (RunResult whole = TilePatternEngine.Run(joined, remesh, pattern, null, new RunOptions { Tries = 1 }))
            {
                Func<RunResult, bool> inPieces = r => r.Tiling.Report.Warnings.Any(w => w.Name == "several_pieces");
                Assert.IsTrue(inPieces(apart), "a soup is in pieces");
                Assert.IsFalse(inPieces(whole), "joined, one surface");
                Assert.Greater(whole.Tiling.FullCount, apart.Tiling.FullCount);
            }
        }

        [Test]
        public void TheLibrarysWeldJoinsWhatJoinVerticesJoinsAndTellsWhereFacesCameFrom()
        {
            PolyMesh dome = TestMeshes.RoundDome();
            int[] group;
            PolyMesh soup = Apart(dome, f => f, out group);
            WeldedMesh welded = soup.Welded();
            Assert.AreEqual(dome.VertexCount, welded.Mesh.VertexCount);
            CollectionAssert.AreEqual(Enumerable.Range(0, dome.FaceCount).ToArray(), welded.FaceSource);
            int[] first;
            PolyMesh joined = soup.JoinVertices(group, out first);
            CollectionAssert.AreEqual(joined.Vertices, welded.Mesh.Vertices);
            CollectionAssert.AreEqual(first, welded.VertexSource);
            // Tiled as the dome; the soup itself is refused, saying to weld.
            var pattern = new PatternOptions { Courses = Courses.Level };
            var remesh = RemeshOptions.ForTile(new TileOptions(), Courses.Level);
            var e = Assert.Throws<InvalidMeshException>(() => TilePatternEngine.Run(soup, remesh, pattern, null, new RunOptions { Tries = 1 }));
            StringAssert.Contains("weld", e.Message);
            using (RunResult run = TilePatternEngine.Run(welded.Mesh, remesh, pattern, null, new RunOptions { Tries = 1 }))
                Assert.Greater(run.Tiling.FullCount, 100);
            Assert.Throws<InvalidArgumentException>(() => soup.Welded(double.NaN));
            Assert.AreEqual(soup.VertexCount, soup.Welded(0.0).Mesh.VertexCount);
        }

        [Test]
        public void ACollapsedEdgeLeavesATriangleAndACollapsedFaceLeavesTheMeshAsItIs()
        {
            // Two quads side by side; joining vertices 2 and 5 (the second quad's right edge)
            // leaves it a triangle, face numbers unchanged.
            double[] xyz = { 0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 1, 0, 1, 1, 0, 2, 1, 0 };
            PolyMesh two = PolyMesh.FromFaces(xyz, new[] { new[] { 0, 1, 4, 3 }, new[] { 1, 2, 5, 4 } });
            int[] first;
            PolyMesh joined = two.JoinVertices(new[] { 0, 1, 2, 3, 4, 2 }, out first);
            Assert.AreEqual(2, joined.FaceCount);
            CollectionAssert.AreEqual(new[] { 1, 2, 4 }, joined.Face(1));
            CollectionAssert.AreEqual(new[] { 0, 1, 2, 3, 4 }, first);
            // Joining 1, 2 and 5 as well leaves the second face two corners: refused.
            Assert.IsNull(two.JoinVertices(new[] { 0, 1, 1, 2, 3, 1 }, out first));
            Assert.IsNull(first);
            // One group per vertex, numbered without a gap.
            Assert.Throws<ArgumentException>(() => two.JoinVertices(new[] { 0, 1 }, out first));
            Assert.Throws<ArgumentException>(() => two.JoinVertices(new[] { 0, 1, 2, 3, 5, 5 }, out first));
            Assert.Throws<ArgumentOutOfRangeException>(() => two.JoinVertices(new[] { 0, 1, 2, 3, 4, -1 }, out first));
            Assert.Throws<ArgumentOutOfRangeException>(() => two.JoinVertices(new[] { 0, 1, 2, 3, 4, int.MaxValue }, out first));
        }
    }
}

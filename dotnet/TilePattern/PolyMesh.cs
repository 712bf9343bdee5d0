// A polygon mesh in plain arrays: the input surface (triangles, quads, n-gons) and the quad
// mesh the remesh stage returns.
using System;
using System.Collections.Generic;
using System.Runtime.CompilerServices;

namespace TilePattern
{
    /// <summary>A mesh welded by <see cref="PolyMesh.Welded"/>, with where its vertices and
    /// faces came from in the mesh given.</summary>
    public sealed class WeldedMesh
    {
        internal WeldedMesh(PolyMesh mesh, int[] vertexSource, int[] faceSource)
        {
            Mesh = mesh;
            this.vertexSource = vertexSource;
            this.faceSource = faceSource;
        }

        readonly int[] vertexSource, faceSource;

        /// <summary>The welded, validated mesh.</summary>
        public PolyMesh Mesh { get; private set; }

        /// <summary>Each vertex's first given vertex (a copy): a field given per vertex is
        /// carried over as <c>field[VertexSource[v]]</c>.</summary>
        public int[] VertexSource { get { return (int[])vertexSource.Clone(); } }

        /// <summary>Each face's given face (a copy; triangles split where cracks were zipped
        /// keep their face's): zones or excluded faces given per face are carried over
        /// through it; a given face in no entry was removed.</summary>
        public int[] FaceSource { get { return (int[])faceSource.Clone(); } }
    }

    /// <summary>An immutable polygon mesh: vertices as xyz triples, faces as a flat list of
    /// vertex indices plus one size per face (face i uses the next FaceSizes[i] indices).
    /// Validation (NaN, indices out of range, non-manifold edges, empty mesh) happens in the
    /// native library when the mesh is used, or with <see cref="TilePatternEngine.Validate"/>.</summary>
    public sealed class PolyMesh
    {
        readonly double[] vertices;
        readonly int[] faceIndices;
        readonly int[] faceSizes;
        readonly int[] faceStarts;

        /// <summary>Copies the arrays. Throws ArgumentException when they do not fit together
        /// (coordinates not a multiple of 3, sizes not adding up to the index count, negative
        /// values); everything else is checked by the library.</summary>
        public PolyMesh(double[] vertices, int[] faceIndices, int[] faceSizes)
        {
            if (vertices == null)
                throw new ArgumentNullException("vertices");
            if (faceIndices == null)
                throw new ArgumentNullException("faceIndices");
            if (faceSizes == null)
                throw new ArgumentNullException("faceSizes");
            if (vertices.Length % 3 != 0)
                throw new ArgumentException("vertices holds xyz triples: its length " + vertices.Length + " is not a multiple of 3", "vertices");
            long total = 0;
            faceStarts = new int[faceSizes.Length];
            for (int f = 0; f < faceSizes.Length; f++)
            {
                if (faceSizes[f] < 0)
                    throw new ArgumentOutOfRangeException("faceSizes", faceSizes[f], "face " + f + " has a negative size");
                faceStarts[f] = (int)total;
                total += faceSizes[f];
                if (total > faceIndices.Length)
                    break;
            }
            if (total != faceIndices.Length)
                throw new ArgumentException("faceSizes add up to " + total + " but faceIndices holds " + faceIndices.Length, "faceSizes");
            for (int k = 0; k < faceIndices.Length; k++)
                if (faceIndices[k] < 0)
                    throw new ArgumentOutOfRangeException("faceIndices", faceIndices[k], "vertex indices are 0-based and not negative");
            this.vertices = (double[])vertices.Clone();
            this.faceIndices = (int[])faceIndices.Clone();
            this.faceSizes = (int[])faceSizes.Clone();
        }

        /// <summary>A mesh from one index array per face.</summary>
        public static PolyMesh FromFaces(double[] vertices, IList<int[]> faces)
        {
            if (faces == null)
                throw new ArgumentNullException("faces");
            var sizes = new int[faces.Count];
            var flat = new List<int>();
            for (int f = 0; f < faces.Count; f++)
            {
                if (faces[f] == null)
                    throw new ArgumentNullException("faces", "face " + f + " is null");
                sizes[f] = faces[f].Length;
                flat.AddRange(faces[f]);
            }
            return new PolyMesh(vertices, flat.ToArray(), sizes);
        }

        /// <summary>xyz triples (a copy).</summary>
        public double[] Vertices { get { return (double[])vertices.Clone(); } }

        /// <summary>All faces' vertex indices in face order (a copy).</summary>
        public int[] FaceIndices { get { return (int[])faceIndices.Clone(); } }

        /// <summary>Vertex count of each face (a copy).</summary>
        public int[] FaceSizes { get { return (int[])faceSizes.Clone(); } }

        public int VertexCount { get { return vertices.Length / 3; } }

        /// <summary>Length of <see cref="FaceIndices"/> (without copying it).</summary>
        internal int FaceIndexLength { get { return faceIndices.Length; } }

        public int FaceCount { get { return faceSizes.Length; } }

        /// <summary>Vertex i as {x, y, z}.</summary>
        public double[] Vertex(int i)
        {
            return new[] { vertices[3 * i], vertices[3 * i + 1], vertices[3 * i + 2] };
        }

        /// <summary>The vertex indices of face f.</summary>
        public int[] Face(int f)
        {
            var face = new int[faceSizes[f]];
            Array.Copy(faceIndices, faceStarts[f], face, 0, face.Length);
            return face;
        }

        /// <summary>Every face's vertex indices.</summary>
        public int[][] Faces()
        {
            var faces = new int[FaceCount][];
            for (int f = 0; f < faces.Length; f++)
                faces[f] = Face(f);
            return faces;
        }

        /// <summary>True when every face is a quad.</summary>
        public bool IsQuadMesh
        {
            get { return Array.TrueForAll(faceSizes, s => s == 4); }
        }

        /// <summary>The centroid of face f's vertices, {x, y, z}.</summary>
        public double[] FaceCenter(int f)
        {
            var c = new double[3];
            int n = faceSizes[f];
            for (int k = 0; k < n; k++)
            {
                int v = faceIndices[faceStarts[f] + k];
                for (int d = 0; d < 3; d++)
                    c[d] += vertices[3 * v + d] / n;
            }
            return c;
        }

        /// <summary>This mesh with the vertices of each group joined into one: vertex i becomes
        /// vertex <paramref name="group"/>[i] (groups numbered from 0, none empty), placed where
        /// the group's first (lowest) vertex is, which <paramref name="firstVertex"/> gives per
        /// joined vertex. Faces keep their numbers and order, so anything given per face still
        /// holds; a corner the join repeats next to itself (a quad with a collapsed edge) is
        /// left out. Returns null (and a null <paramref name="firstVertex"/>) when a face would
        /// keep fewer than three different corners, or a corner twice apart (pinched): such a
        /// mesh is better given as it is.
        /// For a mesh whose faces do not share their vertices along seams (a polysurface meshed
        /// face by face, an STL), which the library takes as separate pieces: group its
        /// vertices by place (in Rhino, the mesh's topology vertices), as the command line
        /// welds a file.</summary>
        public PolyMesh JoinVertices(int[] group, out int[] firstVertex)
        {
            if (group == null)
                throw new ArgumentNullException("group");
            if (group.Length != VertexCount)
                throw new ArgumentException("group has " + group.Length + " items for a mesh of " + VertexCount + " vertices: give one per vertex", "group");
            int count = 0;
            foreach (int g in group)
            {
                if (g < 0 || g >= VertexCount)
                    throw new ArgumentOutOfRangeException("group", g, "groups are numbered from 0, fewer than the " + VertexCount + " vertices");
                count = Math.Max(count, g + 1);
            }
            var first = new int[count];
            for (int g = 0; g < count; g++)
                first[g] = -1;
            for (int i = 0; i < group.Length; i++)
                if (first[group[i]] < 0)
                    first[group[i]] = i;
            int empty = Array.IndexOf(first, -1);
            if (empty >= 0)
                throw new ArgumentException("group " + empty + " has no vertex: number the groups 0 to " + (count - 1) + " without a gap", "group");
            var xyz = new double[3 * count];
            for (int g = 0; g < count; g++)
                Array.Copy(vertices, 3 * first[g], xyz, 3 * g, 3);
            var faces = new int[FaceCount][];
            for (int f = 0; f < faces.Length; f++)
            {
                var corners = new List<int>(faceSizes[f]);
                for (int k = 0; k < faceSizes[f]; k++)
                {
                    int v = group[faceIndices[faceStarts[f] + k]];
                    if (corners.Count == 0 || corners[corners.Count - 1] != v)
                        corners.Add(v);
                }
                while (corners.Count > 1 && corners[0] == corners[corners.Count - 1])
                    corners.RemoveAt(corners.Count - 1);
                if (new HashSet<int>(corners).Count < 3 || new HashSet<int>(corners).Count != corners.Count)
                {
                    firstVertex = null;
                    return null;
                }
                faces[f] = corners.ToArray();
            }
            firstVertex = first;
            return FromFaces(xyz, faces);
        }

        /// <summary>This mesh as the command line reads a file (tp_mesh_new_welded): vertices
        /// closer than <paramref name="relativeTolerance"/> times its size (the bounding-box
        /// diagonal of the vertices faces use) joined, the faces this collapses or repeats
        /// removed, the cracks of a triangle mesh zipped where patches meshed apart meet (their
        /// triangles split) and faces turned to agree with their neighbours, validated. For a
        /// triangle soup (an STL) or patches joined without welding, which the stages take as
        /// pieces. 0 joins nothing (faces are still turned); the command line's default is
        /// 1e-6. Unlike <see cref="JoinVertices"/>, faces may be removed or split:
        /// <see cref="WeldedMesh.FaceSource"/> carries data given per face over.
        /// Throws <see cref="InvalidArgumentException"/> for a tolerance outside 0 to below 1,
        /// <see cref="InvalidMeshException"/> for a mesh still not valid (faces and vertices
        /// named as given).</summary>
        public WeldedMesh Welded(double relativeTolerance = 1e-6)
        {
            // The library loaded first, then the P/Invoke in a method of its own (see
            // NativeLibraryLoader).
            Native.EnsureReady();
            return WeldedCore(relativeTolerance);
        }

        [MethodImpl(MethodImplOptions.NoInlining)]
        WeldedMesh WeldedCore(double relativeTolerance)
        {
            uint[] indices, sizes;
            NativeArrays(out indices, out sizes);
            MeshHandle handle;
            int status = NativeMethods.tp_mesh_new_welded(
                vertices, Native.Size(VertexCount), indices, Native.Size(indices.Length), sizes, Native.Size(sizes.Length), relativeTolerance, out handle);
            if (status != 0)
            {
                handle.Dispose();
                Native.Check(status);
            }
            using (handle)
            {
                PolyMesh mesh = FromHandle(handle);
                var vertexSource = new uint[mesh.VertexCount];
                var faceSource = new uint[mesh.FaceCount];
                Native.Check(NativeMethods.tp_mesh_copy_sources(handle, vertexSource, Native.Size(vertexSource.Length), faceSource, Native.Size(faceSource.Length)));
                return new WeldedMesh(mesh, ToInt(vertexSource), ToInt(faceSource));
            }
        }

        /// <summary>The face arrays as tp_mesh_new takes them.</summary>
        void NativeArrays(out uint[] indices, out uint[] sizes)
        {
            indices = new uint[faceIndices.Length];
            for (int k = 0; k < indices.Length; k++)
                indices[k] = (uint)faceIndices[k];
            sizes = new uint[faceSizes.Length];
            for (int f = 0; f < sizes.Length; f++)
                sizes[f] = (uint)faceSizes[f];
        }

        /// <summary>Builds and validates the native mesh (tp_mesh_new).</summary>
        [MethodImpl(MethodImplOptions.NoInlining)]
        internal MeshHandle CreateHandle()
        {
            uint[] indices, sizes;
            NativeArrays(out indices, out sizes);
            MeshHandle handle;
            int status = NativeMethods.tp_mesh_new(
                vertices, Native.Size(VertexCount), indices, Native.Size(indices.Length), sizes, Native.Size(sizes.Length), out handle);
            if (status != 0)
            {
                handle.Dispose();
                Native.Check(status);
            }
            return handle;
        }

        /// <summary>Reads a native mesh back (tp_mesh_counts and the copy functions).</summary>
        [MethodImpl(MethodImplOptions.NoInlining)]
        internal static PolyMesh FromHandle(MeshHandle handle)
        {
            UIntPtr vertexCount, faceCount, indexCount;
            Native.Check(NativeMethods.tp_mesh_counts(handle, out vertexCount, out faceCount, out indexCount));
            var xyz = new double[checked(3 * Native.Count(vertexCount))];
            var indices = new uint[Native.Count(indexCount)];
            var sizes = new uint[Native.Count(faceCount)];
            Native.Check(NativeMethods.tp_mesh_copy_vertices(handle, xyz, Native.Size(xyz.Length)));
            Native.Check(NativeMethods.tp_mesh_copy_faces(handle, indices, Native.Size(indices.Length), sizes, Native.Size(sizes.Length)));
            return new PolyMesh(xyz, ToInt(indices), ToInt(sizes));
        }

        internal static int[] ToInt(uint[] values)
        {
            var result = new int[values.Length];
            for (int k = 0; k < values.Length; k++)
                result[k] = checked((int)values[k]);
            return result;
        }
    }
}

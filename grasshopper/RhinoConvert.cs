// Every conversion between Rhino geometry and the wrapper's plain arrays, in one place. The
// decisions (which loops make which piece, closing points, frames) are the wrapper's
// (TilePieces, TileOutputs); this file only builds the Rhino objects.
using System;
using System.Collections.Generic;
using Rhino.Geometry;

namespace TilePattern.Gh
{
    internal static class RhinoConvert
    {
        /// <summary>A Rhino mesh as a PolyMesh: each face as a triangle or a quad, in order
        /// (n-gons are taken as their triangles/quads; the library accepts both). Faces wound
        /// against their neighbours are turned on a copy (Rhino's UnifyNormals, as the command
        /// line turns a file's); <paramref name="turnedFaces"/> says how many, and the caller's
        /// mesh is never changed. Vertices at one place are joined into one, as Rhino's mesh
        /// topology joins them (a polysurface meshed face by face keeps each face's own
        /// vertices along the seams, which the library would take as separate pieces, remeshed
        /// and cut apart): <paramref name="vertexSource"/> then gives each joined vertex's
        /// first vertex in the Rhino mesh (for inputs given per vertex), and is null when
        /// nothing was joined; <paramref name="notJoined"/> says why vertices at one place were
        /// left apart (null when none were). Faces keep their numbers either way.</summary>
        public static PolyMesh ToPolyMesh(Mesh mesh, out int turnedFaces, out int[] vertexSource, out string notJoined)
        {
            PolyMesh asGiven = ToPolyMesh(mesh, out turnedFaces);
            vertexSource = null;
            notJoined = null;
            var places = mesh.TopologyVertices;
            if (places.Count >= mesh.Vertices.Count)
                return asGiven;
            var group = new int[mesh.Vertices.Count];
            for (int v = 0; v < group.Length; v++)
                group[v] = places.TopologyVertexIndex(v);
            int[] first;
            PolyMesh joined = asGiven.JoinVertices(group, out first);
            if (joined == null)
            {
                notJoined = "joined, a face would collapse or pinch (corners at one place: Rhino's CullDegenerateMeshFaces removes such faces)";
                return asGiven;
            }
            try
            {
                // Joined, a mesh may no longer be one the library takes (three faces on an
                // edge, two faces on the same corners): then it is given as it was.
                TilePatternEngine.Validate(joined);
            }
            catch (TilePatternException e)
            {
                notJoined = "joined, the library would refuse the mesh: " + e.Message;
                return asGiven;
            }
            vertexSource = first;
            return joined;
        }

        static PolyMesh ToPolyMesh(Mesh mesh, out int turnedFaces)
        {
            if (mesh == null)
                throw new ArgumentNullException("mesh");
            turnedFaces = mesh.UnifyNormals(true);
            if (turnedFaces > 0)
            {
                mesh = mesh.DuplicateMesh();
                turnedFaces = mesh.UnifyNormals();
            }
            var xyz = new double[3 * mesh.Vertices.Count];
            for (int i = 0; i < mesh.Vertices.Count; i++)
            {
                Point3d p = mesh.Vertices.Point3dAt(i);
                xyz[3 * i] = p.X;
                xyz[3 * i + 1] = p.Y;
                xyz[3 * i + 2] = p.Z;
            }
            var indices = new List<int>(4 * mesh.Faces.Count);
            var sizes = new int[mesh.Faces.Count];
            for (int f = 0; f < mesh.Faces.Count; f++)
            {
                MeshFace face = mesh.Faces[f];
                indices.Add(face.A);
                indices.Add(face.B);
                indices.Add(face.C);
                if (face.IsQuad)
                    indices.Add(face.D);
                sizes[f] = face.IsQuad ? 4 : 3;
            }
            return new PolyMesh(xyz, indices.ToArray(), sizes);
        }

        /// <summary>A PolyMesh as a Rhino mesh with normals (faces above 4 vertices as fans).</summary>
        public static Mesh ToRhinoMesh(PolyMesh polyMesh)
        {
            var mesh = new Mesh();
            double[] xyz = polyMesh.Vertices;
            for (int i = 0; i < polyMesh.VertexCount; i++)
                mesh.Vertices.Add(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
            for (int f = 0; f < polyMesh.FaceCount; f++)
            {
                int[] face = polyMesh.Face(f);
                if (face.Length == 4)
                    mesh.Faces.AddFace(face[0], face[1], face[2], face[3]);
                else
                    for (int k = 1; k + 1 < face.Length; k++)
                        mesh.Faces.AddFace(face[0], face[k], face[k + 1]);
            }
            mesh.Normals.ComputeNormals();
            mesh.Compact();
            return mesh;
        }

        static Point3d Point(double[] xyz, int at)
        {
            return new Point3d(xyz[at], xyz[at + 1], xyz[at + 2]);
        }

        /// <summary>The tile's frame: origin, length axis x, width axis y (thickness along z).</summary>
        public static Plane ToPlane(TileFrame frame)
        {
            return new Plane(Point(frame.Origin, 0), new Vector3d(frame.XAxis[0], frame.XAxis[1], frame.XAxis[2]),
                new Vector3d(frame.YAxis[0], frame.YAxis[1], frame.YAxis[2]));
        }

        /// <summary>The tile as a solid: its box, or for a cut tile every piece (outer loop and
        /// holes) extruded by the thickness, all pieces in one Brep. Null when a piece cannot be
        /// made: the caller reports it and never falls back to the uncut box.</summary>
        public static Brep ToBrep(Tile tile, TilePiece[] pieces, double tolerance)
        {
            if (tile.Outline.Length == 0)
            {
                var corners = new List<Point3d>(8);
                foreach (double[] c in TilePieces.BoxCorners(tile))
                    corners.Add(Point(c, 0));
                return Brep.CreateFromBox(corners);
            }
            double[] up = TilePieces.Extrusion(tile);
            Brep solid = null;
            foreach (TilePiece piece in pieces)
            {
                var loops = new List<Curve>();
                foreach (double[] loop in piece.Loops)
                {
                    var points = new List<Point3d>(loop.Length / 3);
                    for (int p = 0; p < loop.Length; p += 3)
                        points.Add(Point(loop, p));
                    loops.Add(new PolylineCurve(points));
                }
                Brep[] faces = Brep.CreatePlanarBreps(loops, tolerance);
                if (faces == null || faces.Length != 1)
                    return null;
                Point3d start = Point(piece.Outer, 0);
                var path = new LineCurve(start, new Point3d(start.X + up[0], start.Y + up[1], start.Z + up[2]));
                Brep extruded = faces[0].Faces[0].CreateExtrusion(path, true);
                if (extruded == null)
                    return null;
                if (solid == null)
                    solid = extruded;
                else
                    solid.Append(extruded);
            }
            return solid;
        }
    }
}

// Every conversion between Rhino geometry and the wrapper's plain arrays, in one place.
using System;
using System.Collections.Generic;
using Rhino.Geometry;

namespace TilePattern.Gh
{
    internal static class RhinoConvert
    {
        /// <summary>A Rhino mesh as a PolyMesh: vertices in order, each face as a triangle or a
        /// quad (n-gons are taken as their triangles/quads; the library accepts both).</summary>
        public static PolyMesh ToPolyMesh(Mesh mesh)
        {
            if (mesh == null)
                throw new ArgumentNullException("mesh");
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

        public static Point3d ToPoint(double[] xyz)
        {
            return new Point3d(xyz[0], xyz[1], xyz[2]);
        }

        public static Vector3d ToVector(double[] xyz)
        {
            return new Vector3d(xyz[0], xyz[1], xyz[2]);
        }

        /// <summary>The tile's frame: origin, length axis x, width axis y (thickness along z).</summary>
        public static Plane ToPlane(Tile tile)
        {
            return new Plane(ToPoint(tile.Origin), ToVector(tile.XAxis), ToVector(tile.YAxis));
        }

        /// <summary>The tile as a solid: its box from the library's 8 corners, or for a boundary
        /// tile its kept outline extruded by the thickness.</summary>
        public static Brep ToBrep(Tile tile, double tolerance)
        {
            if (tile.Outline.Length > 0)
            {
                Brep cut = CutSolid(tile, tolerance);
                if (cut != null)
                    return cut;
            }
            var corners = new Point3d[8];
            for (int i = 0; i < 8; i++)
                corners[i] = ToPoint(tile.Corner(i));
            return Brep.CreateFromBox(corners);
        }

        static Brep CutSolid(Tile tile, double tolerance)
        {
            var loops = new List<Curve>();
            for (int l = 0; l < tile.Outline.Length; l++)
            {
                double[] xyz = tile.OutlineInModel(l);
                var points = new List<Point3d>();
                for (int p = 0; p < xyz.Length; p += 3)
                    points.Add(new Point3d(xyz[p], xyz[p + 1], xyz[p + 2]));
                points.Add(points[0]);
                loops.Add(new PolylineCurve(points));
            }
            Brep[] faces = Brep.CreatePlanarBreps(loops, tolerance);
            if (faces == null || faces.Length == 0)
                return null;
            Point3d origin = ToPoint(tile.Origin);
            double[] z = tile.ZAxis;
            var top = new Point3d(origin.X + z[0] * tile.Thickness, origin.Y + z[1] * tile.Thickness, origin.Z + z[2] * tile.Thickness);
            var path = new LineCurve(origin, top);
            return faces[0].Faces[0].CreateExtrusion(path, true);
        }
    }
}

// Reference stub of RhinoCommon's Rhino.Geometry (see Rhino.cs).
using System;
using System.Collections.Generic;

namespace Rhino.Runtime
{
    public abstract class CommonObject
    {
        internal CommonObject() { }
    }
}

namespace Rhino.Geometry
{
    public abstract class GeometryBase : Rhino.Runtime.CommonObject
    {
        internal GeometryBase() { }
        public BoundingBox GetBoundingBox(bool accurate) { throw null; }
    }

    public class Mesh : GeometryBase
    {
        public Mesh() { }
        public Rhino.Geometry.Collections.MeshVertexList Vertices { get { throw null; } }
        public Rhino.Geometry.Collections.MeshFaceList Faces { get { throw null; } }
        public Rhino.Geometry.Collections.MeshVertexNormalList Normals { get { throw null; } }
        public Rhino.Geometry.Collections.MeshTopologyVertexList TopologyVertices { get { throw null; } }
        public bool Compact() { throw null; }
        public Mesh DuplicateMesh() { throw null; }
        public int UnifyNormals() { throw null; }
        public int UnifyNormals(bool countOnly) { throw null; }
    }

    public struct MeshFace
    {
        public int A { get { throw null; } set { } }
        public int B { get { throw null; } set { } }
        public int C { get { throw null; } set { } }
        public int D { get { throw null; } set { } }
        public bool IsQuad { get { throw null; } }
    }

    public struct Point3d
    {
        public Point3d(double x, double y, double z) { throw null; }
        public double X { get { throw null; } set { } }
        public double Y { get { throw null; } set { } }
        public double Z { get { throw null; } set { } }
    }

    public struct Vector3d
    {
        public Vector3d(double x, double y, double z) { throw null; }
        public static Vector3d Unset { get { throw null; } }
        public double X { get { throw null; } set { } }
        public double Y { get { throw null; } set { } }
        public double Z { get { throw null; } set { } }
        public bool IsValid { get { throw null; } }
        public bool IsZero { get { throw null; } }
    }

    public struct Plane
    {
        public Plane(Point3d origin, Vector3d xDirection, Vector3d yDirection) { throw null; }
    }

    public struct BoundingBox
    {
        public static BoundingBox Empty { get { throw null; } }
        public void Union(BoundingBox other) { }
    }

    public class Brep : GeometryBase
    {
        public Brep() { }
        public static Brep CreateFromBox(IEnumerable<Point3d> corners) { throw null; }
        public static Brep[] CreatePlanarBreps(IEnumerable<Curve> inputLoops, double tolerance) { throw null; }
        public Rhino.Geometry.Collections.BrepFaceList Faces { get { throw null; } }
        public void Append(Brep other) { }
    }

    public abstract class Surface : GeometryBase
    {
        internal Surface() { }
    }

    public abstract class SurfaceProxy : Surface
    {
        internal SurfaceProxy() { }
    }

    public class BrepFace : SurfaceProxy
    {
        internal BrepFace() { }
        public Brep CreateExtrusion(Curve pathCurve, bool cap) { throw null; }
    }

    public class Curve : GeometryBase
    {
        internal Curve() { }
        public PolylineCurve ToPolyline(double tolerance, double angleTolerance, double minimumLength, double maximumLength) { throw null; }
    }

    public class PolylineCurve : Curve
    {
        public PolylineCurve(IEnumerable<Point3d> points) { }
        public int PointCount { get { throw null; } }
        public Point3d Point(int index) { throw null; }
    }

    public class LineCurve : Curve
    {
        public LineCurve(Point3d from, Point3d to) { }
    }
}

namespace Rhino.Geometry.Collections
{
    public class MeshVertexList
    {
        internal MeshVertexList() { }
        public int Count { get { throw null; } }
        public Point3d Point3dAt(int index) { throw null; }
        public int Add(double x, double y, double z) { throw null; }
    }

    public class MeshTopologyVertexList
    {
        internal MeshTopologyVertexList() { }
        public int Count { get { throw null; } }
        public int TopologyVertexIndex(int vertexIndex) { throw null; }
    }

    public class MeshFaceList
    {
        internal MeshFaceList() { }
        public int Count { get { throw null; } }
        public MeshFace this[int index] { get { throw null; } }
        public int AddFace(int vertex1, int vertex2, int vertex3) { throw null; }
        public int AddFace(int vertex1, int vertex2, int vertex3, int vertex4) { throw null; }
    }

    public class MeshVertexNormalList
    {
        internal MeshVertexNormalList() { }
        public bool ComputeNormals() { throw null; }
    }

    public class BrepFaceList
    {
        internal BrepFaceList() { }
        public BrepFace this[int index] { get { throw null; } }
    }
}

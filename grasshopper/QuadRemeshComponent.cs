// Stage 1: a triangle (or polygon) surface mesh to near-square quads of half a tile plus a joint.
using System;
using System.Collections.Generic;
using Grasshopper.Kernel;
using Grasshopper.Kernel.Parameters;
using Rhino.Geometry;

namespace TilePattern.Gh
{
    public class QuadRemeshComponent : BackgroundComponent<PolyMesh>
    {
        public QuadRemeshComponent()
            : base("Quad Remesh", "QRemesh",
                "Quadrangulates a surface mesh into near-square quads whose edge is (tile length + joint) / 2, or for level courses at least a course's height (width + joint), aligned with the principal curvature, a direction, a rotated curvature field or the designer's own field (e.g. stress or thrust directions, one vector per mesh vertex or face), and near guide curves along the curves. Solves in the background; right-click to cancel.",
                "1 Mesh")
        {
        }

        public override Guid ComponentGuid { get { return new Guid("43c9a107-4b53-4bae-8ab4-b197aad85ebe"); } }

        protected override System.Drawing.Bitmap Icon { get { return Icons.Load("QuadRemesh"); } }

        public override GH_Exposure Exposure { get { return GH_Exposure.primary; } }

        protected override void RegisterInputParams(GH_InputParamManager pManager)
        {
            pManager.AddMeshParameter("Mesh", "M", "The shell's surface: a triangle, quad or mixed mesh, in model units", GH_ParamAccess.item);
            pManager.AddNumberParameter("Tile length", "L", "Length of a full tile in model units (default: 280 mm in the document's units)", GH_ParamAccess.item);
            pManager.AddNumberParameter("Joint", "J", "Mortar joint in model units (default: 10 mm in the document's units)", GH_ParamAccess.item);
            pManager.AddVectorParameter("Direction", "D", "Optional: align the quads with this direction (projected onto the surface) instead of the curvature", GH_ParamAccess.item);
            pManager.AddNumberParameter("Angle", "A", "Optional: rotate the curvature field by this angle", GH_ParamAccess.item);
            pManager.AddBooleanParameter("Shape-up", "S", "Pull faces towards squares without leaving the surface", GH_ParamAccess.item, false);
            // Appended inputs keep the indices above (saved definitions wire by index).
            pManager.AddNumberParameter("Tile width", "W", "Width of a tile in model units (default: 140 mm in the document's units); with level courses the quads are at least width + joint high", GH_ParamAccess.item);
            pManager.AddIntegerParameter("Courses", "C", "As Tile Pattern's Courses: 1 = level (default), quads of max((length + joint) / 2, width + joint); 0 = free, quads of (length + joint) / 2", GH_ParamAccess.item, (int)Courses.Level);
            pManager.AddVectorParameter("Field", "F", "Optional: the designer's direction field (e.g. principal stress or thrust directions from a structural analysis), one vector per mesh vertex or one per mesh face, in mesh order; signs and lengths do not matter", GH_ParamAccess.list);
            pManager.AddNumberParameter("Field weight", "FW", "Share of the Field against the curvature field (or Direction / Angle), 0 to 1 (default 1: the field alone)", GH_ParamAccess.item, 1.0);
            pManager.AddCurveParameter("Guides", "G", "Optional: guide curves the quad rows follow near them (within 2 quad edges, falling off), on or near the mesh, in model units; turned into polylines at the document's tolerance (5 degrees angle tolerance)", GH_ParamAccess.list);
            pManager.AddNumberParameter("Guide weight", "GW", "Share of the Guides on the curves against every other source (curvature, Direction / Angle, Field), 0 to 1 (default 1: the guides alone on them)", GH_ParamAccess.item, 1.0);
            pManager.AddBooleanParameter("Creases", "Cr", "Split the mesh where its faces turn sharply (a groin vault's groins, a fold) and give each part quads of its own, as masons lay each web in its own courses (default true); give Tile Boxes the same", GH_ParamAccess.item, true);
            pManager.AddNumberParameter("Renormalisation", "Rn", "Strength that places the field's cones, and with them where rows end: any number from 0 (default 0.5). Other strengths give other, equally valid quads whose tiles may fit better: where Tile Boxes reports cuts or wide joints, try 1 and 0.25 and keep the tiles that fit best (the command line's run does this)", GH_ParamAccess.item, 0.5);
            pManager.AddBooleanParameter("Smooth", "Sm", "Follow neither the curvature nor a direction: the boundary and smoothness alone orient the quads (default false; Tile Surface's second try). Where the curvature lines converge (a cone, a funnel, a bend) its quads end fewer rows and the tiles are cut less; ignored when a Direction or Angle is given", GH_ParamAccess.item, false);
            for (int i = 1; i <= 4; i++)
                pManager[i].Optional = true;
            pManager[6].Optional = true;
            pManager[8].Optional = true;
            pManager[9].Optional = true;
            pManager[10].Optional = true;
            pManager[11].Optional = true;
            pManager[12].Optional = true;
            pManager[13].Optional = true;
            pManager[14].Optional = true;
            ((Param_Number)pManager[4]).AngleParameter = true;
            NameCourses((Param_Integer)pManager[7]);
        }

        /// <summary>Angle tolerance (radians) of the guide curves' polylines: 5 degrees, as
        /// Rhino's ConvertCurveToPolyline defaults to.</summary>
        const double GuideAngleTolerance = 5.0 * Math.PI / 180.0;

        protected override void RegisterOutputParams(GH_OutputParamManager pManager)
        {
            pManager.AddMeshParameter("Quad mesh", "Q", "Near-square quads", GH_ParamAccess.item);
            pManager.AddNumberParameter("Edge", "E", "Target quad edge used: (tile length + joint) / 2, or max of that and width + joint for level courses", GH_ParamAccess.item);
        }

        protected override void SolveInstance(IGH_DataAccess DA)
        {
            Mesh mesh = null;
            if (!DA.GetData(0, ref mesh) || mesh == null)
                return;
            TileDefaults defaults = Defaults();
            double length = defaults.Length, joint = defaults.Joint, width = defaults.Width, angle = 0.0;
            int courses = (int)Courses.Level;
            Vector3d direction = Vector3d.Unset;
            bool shapeUp = false;
            DA.GetData(1, ref length);
            DA.GetData(2, ref joint);
            bool hasDirection = DA.GetData(3, ref direction) && direction.IsValid && !direction.IsZero;
            bool hasAngle = DA.GetData(4, ref angle);
            DA.GetData(5, ref shapeUp);
            DA.GetData(6, ref width);
            DA.GetData(7, ref courses);
            var field = new List<Vector3d>();
            DA.GetDataList(8, field);
            double fieldWeight = 1.0;
            DA.GetData(9, ref fieldWeight);
            var curves = new List<Curve>();
            DA.GetDataList(10, curves);
            double guideWeight = 1.0;
            DA.GetData(11, ref guideWeight);
            bool creases = true;
            DA.GetData(12, ref creases);
            double renormalisation = 0.5;
            DA.GetData(13, ref renormalisation);
            bool smooth = false;
            DA.GetData(14, ref smooth);
            if (!CheckCourses(courses))
                return;
            // An angle parameter gives radians unless the user switched it to degrees.
            if (hasAngle && !((Param_Number)Params.Input[4]).UseDegrees)
                angle = angle * 180.0 / Math.PI;
            if (hasDirection && hasAngle)
                AddRuntimeMessage(GH_RuntimeMessageLevel.Warning, "Both a direction and an angle are given: the direction is used.");

            var options = new RemeshOptions { TargetEdge = TileOptions.QuadEdgeOf(length, width, joint, (Courses)courses), ShapeUp = shapeUp, Creases = creases, Renormalisation = renormalisation };
            if (hasDirection)
            {
                options.Direction = FieldDirection.Vector;
                options.DirectionVector = new[] { direction.X, direction.Y, direction.Z };
            }
            else if (hasAngle)
            {
                options.Direction = FieldDirection.Angle;
                options.AngleDegrees = angle;
            }
            else if (smooth)
                options.Direction = FieldDirection.Smooth;
            PolyMesh surface;
            int[] joined;
            if (!ReadMesh(mesh, "surface", out surface, out joined))
                return;
            if (field.Count > 0)
            {
                if (field.Count != mesh.Vertices.Count && field.Count != mesh.Faces.Count)
                {
                    AddRuntimeMessage(GH_RuntimeMessageLevel.Error, "Field has " + field.Count + " vectors but the mesh has " + mesh.Vertices.Count
                        + " vertices and " + mesh.Faces.Count + " faces: give one vector per vertex or one per face.");
                    return;
                }
                var vectors = new double[field.Count][];
                for (int i = 0; i < field.Count; i++)
                {
                    Vector3d v = field[i];
                    if (!v.IsValid || v.IsZero)
                    {
                        AddRuntimeMessage(GH_RuntimeMessageLevel.Error, "Field vector " + i + " is " + (v.IsValid ? "zero" : "invalid")
                            + ": every vector must be a non-zero direction.");
                        return;
                    }
                    vectors[i] = new[] { v.X, v.Y, v.Z };
                }
                // One per vertex of the Rhino mesh: each joined vertex takes its first vertex's
                // (faces keep their numbers, so a field per face stays as it is).
                if (joined != null && field.Count == mesh.Vertices.Count)
                    vectors = Array.ConvertAll(joined, v => vectors[v]);
                else if (joined != null && joined.Length == mesh.Faces.Count)
                {
                    // The library tells a field per vertex from one per face by its count, and
                    // the joined mesh has as many vertices as faces.
                    AddRuntimeMessage(GH_RuntimeMessageLevel.Error, "Field has one vector per face, but once its vertices at one place are joined the mesh has as many vertices as faces ("
                        + mesh.Faces.Count + "), so a field per face cannot be told from one per vertex: give one vector per vertex of the mesh.");
                    return;
                }
                options.Field = vectors;
                options.FieldWeight = fieldWeight;
            }
            var guides = new List<double[][]>();
            for (int c = 0; c < curves.Count; c++)
            {
                PolylineCurve polyline = curves[c] == null ? null : curves[c].ToPolyline(DocumentTolerance(), GuideAngleTolerance, 0.0, 0.0);
                if (polyline == null || polyline.PointCount < 2)
                {
                    AddRuntimeMessage(GH_RuntimeMessageLevel.Error, "Guide curve " + c + " could not be turned into a polyline: give a valid curve.");
                    return;
                }
                var points = new double[polyline.PointCount][];
                for (int i = 0; i < points.Length; i++)
                {
                    Point3d p = polyline.Point(i);
                    points[i] = new[] { p.X, p.Y, p.Z };
                }
                guides.Add(points);
            }
            if (guides.Count > 0)
            {
                options.Guides = guides.ToArray();
                options.GuideWeight = guideWeight;
            }
            var key = new InputKey().Add(surface).Add(options.TargetEdge).Add(shapeUp).Add((int)options.Direction)
                .Add(options.AngleDegrees).Add(hasDirection ? direction.X : 0).Add(hasDirection ? direction.Y : 0).Add(hasDirection ? direction.Z : 0);
            // The field in the key too, so a changed field solves again.
            key.Add(field.Count).Add(options.FieldWeight);
            foreach (Vector3d v in field)
                key.Add(v.X).Add(v.Y).Add(v.Z);
            // The guides' polylines too.
            key.Add(guides.Count).Add(options.GuideWeight);
            foreach (double[][] points in guides)
            {
                key.Add(points.Length);
                foreach (double[] p in points)
                    key.Add(p[0]).Add(p[1]).Add(p[2]);
            }
            PolyMesh quads = Solve(DA, key, (token, progress) => TilePatternEngine.Remesh(surface, options, progress, token));
            if (quads == null)
                return;
            if (!quads.IsQuadMesh)
                AddRuntimeMessage(GH_RuntimeMessageLevel.Remark, "Some faces are not quads; they get no tile.");
            DA.SetData(0, RhinoConvert.ToRhinoMesh(quads));
            DA.SetData(1, options.TargetEdge);
        }
    }
}

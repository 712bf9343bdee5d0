// Stage 1: a triangle (or polygon) surface mesh to near-square quads of half a tile plus a joint.
using System;
using Grasshopper.Kernel;
using Rhino.Geometry;

namespace TilePattern.Gh
{
    public class QuadRemeshComponent : ComponentBase
    {
        public QuadRemeshComponent()
            : base("Quad Remesh", "QRemesh",
                "Quadrangulates a surface mesh into near-square quads whose edge is (tile length + joint) / 2, aligned with the principal curvature, a direction or a rotated curvature field. Escape cancels it.",
                "1 Mesh")
        {
        }

        public override Guid ComponentGuid { get { return new Guid("43c9a107-4b53-4bae-8ab4-b197aad85ebe"); } }

        protected override System.Drawing.Bitmap Icon { get { return Icons.Load("QuadRemesh"); } }

        public override GH_Exposure Exposure { get { return GH_Exposure.primary; } }

        protected override void RegisterInputParams(GH_InputParamManager pManager)
        {
            pManager.AddMeshParameter("Mesh", "M", "The shell's surface: a triangle, quad or mixed mesh, in model units", GH_ParamAccess.item);
            pManager.AddNumberParameter("Tile length", "L", "Length of a full tile in model units (0.28 = 280 mm in a metre model)", GH_ParamAccess.item, 0.28);
            pManager.AddNumberParameter("Joint", "J", "Mortar joint in model units", GH_ParamAccess.item, 0.01);
            pManager.AddVectorParameter("Direction", "D", "Optional: align the quads with this direction (projected onto the surface) instead of the curvature", GH_ParamAccess.item);
            pManager.AddNumberParameter("Angle", "A", "Optional: rotate the curvature field by this many degrees", GH_ParamAccess.item);
            pManager.AddBooleanParameter("Shape-up", "S", "Pull faces towards squares without leaving the surface", GH_ParamAccess.item, false);
            pManager[3].Optional = true;
            pManager[4].Optional = true;
        }

        protected override void RegisterOutputParams(GH_OutputParamManager pManager)
        {
            pManager.AddMeshParameter("Quad mesh", "Q", "Near-square quads", GH_ParamAccess.item);
            pManager.AddNumberParameter("Edge", "E", "Target quad edge used: (tile length + joint) / 2", GH_ParamAccess.item);
        }

        protected override void SolveInstance(IGH_DataAccess DA)
        {
            Mesh mesh = null;
            double length = 0.28, joint = 0.01, angle = 0.0;
            Vector3d direction = Vector3d.Unset;
            bool shapeUp = false;
            if (!DA.GetData(0, ref mesh) || mesh == null)
                return;
            DA.GetData(1, ref length);
            DA.GetData(2, ref joint);
            bool hasDirection = DA.GetData(3, ref direction) && direction.IsValid && !direction.IsZero;
            bool hasAngle = DA.GetData(4, ref angle);
            DA.GetData(5, ref shapeUp);
            if (hasDirection && hasAngle)
                AddRuntimeMessage(GH_RuntimeMessageLevel.Warning, "Both a direction and an angle are given: the direction is used.");

            Run(() =>
            {
                var options = new RemeshOptions { TargetEdge = (length + joint) / 2.0, ShapeUp = shapeUp };
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
                using (var escape = new EscapeWatcher())
                {
                    PolyMesh quads = TilePatternEngine.Remesh(RhinoConvert.ToPolyMesh(mesh), options, escape, escape.Token);
                    if (!quads.IsQuadMesh)
                        AddRuntimeMessage(GH_RuntimeMessageLevel.Remark, "Some faces are not quads; they get no tile.");
                    DA.SetData(0, RhinoConvert.ToRhinoMesh(quads));
                    DA.SetData(1, options.TargetEdge);
                }
            });
        }
    }
}

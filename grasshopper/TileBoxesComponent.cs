// Stage 3: a box per matched pair, a half tile per unpaired quad, boundary tiles cut to the
// surface; previewed with full, half and cut tiles in different colours.
using System;
using System.Collections.Generic;
using System.Drawing;
using Grasshopper.Kernel;
using Rhino.Display;
using Rhino.Geometry;

namespace TilePattern.Gh
{
    public class TileBoxesComponent : ComponentBase
    {
        static readonly DisplayMaterial FullMaterial = new DisplayMaterial(Color.FromArgb(200, 96, 48));
        static readonly DisplayMaterial HalfMaterial = new DisplayMaterial(Color.FromArgb(60, 120, 200));
        static readonly DisplayMaterial BoundaryMaterial = new DisplayMaterial(Color.FromArgb(230, 190, 40));

        // What the preview draws: the breps of the last solution, by kind.
        readonly List<KeyValuePair<Brep, TileKind>> preview = new List<KeyValuePair<Brep, TileKind>>();
        BoundingBox previewBox = BoundingBox.Empty;

        public TileBoxesComponent()
            : base("Tile Boxes", "TBoxes",
                "Builds the tiles of a pattern: a box per matched pair (full tile), a half tile per unpaired quad, tiles cut to the surface's boundary; with cut-list labels, frames and laying order. Preview: full tiles terracotta, half tiles blue, cut tiles yellow.",
                "3 Tiles")
        {
        }

        public override Guid ComponentGuid { get { return new Guid("98da570f-102e-417f-970e-1b135716ec49"); } }

        protected override Bitmap Icon { get { return Icons.Load("TileBoxes"); } }

        public override GH_Exposure Exposure { get { return GH_Exposure.primary; } }

        protected override void RegisterInputParams(GH_InputParamManager pManager)
        {
            pManager.AddGenericParameter("Pattern", "P", "Pattern from Tile Pattern", GH_ParamAccess.item);
            pManager.AddMeshParameter("Quad mesh", "Q", "Optional: the quad mesh (default: the one the pattern was solved on)", GH_ParamAccess.item);
            pManager.AddNumberParameter("Length", "L", "Tile length in model units", GH_ParamAccess.item, 0.28);
            pManager.AddNumberParameter("Width", "W", "Tile width in model units", GH_ParamAccess.item, 0.14);
            pManager.AddNumberParameter("Thickness", "T", "Tile thickness in model units", GH_ParamAccess.item, 0.015);
            pManager.AddNumberParameter("Joint", "J", "Mortar joint in model units", GH_ParamAccess.item, 0.01);
            pManager.AddMeshParameter("Surface", "S", "Optional: the input surface; tiles are cut to its boundary (default: the quad mesh's boundary)", GH_ParamAccess.item);
            pManager[1].Optional = true;
            pManager[6].Optional = true;
        }

        protected override void RegisterOutputParams(GH_OutputParamManager pManager)
        {
            pManager.AddBrepParameter("Full tiles", "F", "Standard tiles over two quads", GH_ParamAccess.list);
            pManager.AddBrepParameter("Half tiles", "H", "Half tiles over one unpaired quad (each needs a cut)", GH_ParamAccess.list);
            pManager.AddBrepParameter("Cut tiles", "C", "Full or half tiles cut to the surface's boundary", GH_ParamAccess.list);
            pManager.AddTextParameter("Labels", "Lb", "Cut-list label of every tile (F, H, B1, ...), in tile order", GH_ParamAccess.list);
            pManager.AddPlaneParameter("Planes", "Pl", "Frame of every tile: origin, length axis x, width axis y", GH_ParamAccess.list);
            pManager.AddIntegerParameter("Steps", "N", "Laying order of every tile, from 0", GH_ParamAccess.list);
            pManager.AddGenericParameter("Tiling", "T", "All tiles and the report, for Tile Report", GH_ParamAccess.item);
        }

        protected override void BeforeSolveInstance()
        {
            preview.Clear();
            previewBox = BoundingBox.Empty;
            base.BeforeSolveInstance();
        }

        protected override void SolveInstance(IGH_DataAccess DA)
        {
            Pattern pattern = Unwrap<Pattern>(DA, 0);
            if (pattern == null)
            {
                AddRuntimeMessage(GH_RuntimeMessageLevel.Error, "Pattern must come from a Tile Pattern component.");
                return;
            }
            Mesh quads = null, surface = null;
            double length = 0.28, width = 0.14, thickness = 0.015, joint = 0.01;
            bool hasQuads = DA.GetData(1, ref quads) && quads != null;
            DA.GetData(2, ref length);
            DA.GetData(3, ref width);
            DA.GetData(4, ref thickness);
            DA.GetData(5, ref joint);
            bool hasSurface = DA.GetData(6, ref surface) && surface != null;

            Run(() =>
            {
                var options = new TileOptions { Length = length, Width = width, Thickness = thickness, Joint = joint };
                PolyMesh cutTo = hasSurface ? RhinoConvert.ToPolyMesh(surface) : null;
                Tiling tiling = hasQuads
                    ? TilePatternEngine.Tiles(RhinoConvert.ToPolyMesh(quads), pattern, options, cutTo)
                    : TilePatternEngine.Tiles(pattern, options, cutTo);
                double tolerance = Rhino.RhinoDoc.ActiveDoc != null ? Rhino.RhinoDoc.ActiveDoc.ModelAbsoluteTolerance : 1e-6;
                var full = new List<Brep>();
                var half = new List<Brep>();
                var cut = new List<Brep>();
                var labels = new List<string>();
                var planes = new List<Plane>();
                var steps = new List<int>();
                foreach (Tile tile in tiling.Tiles)
                {
                    Brep brep = RhinoConvert.ToBrep(tile, tolerance);
                    if (brep == null)
                        AddRuntimeMessage(GH_RuntimeMessageLevel.Warning, "Tile " + tile.Index + " could not be turned into a Brep.");
                    else
                    {
                        (tile.Kind == TileKind.Full ? full : tile.Kind == TileKind.Half ? half : cut).Add(brep);
                        preview.Add(new KeyValuePair<Brep, TileKind>(brep, tile.Kind));
                        previewBox.Union(brep.GetBoundingBox(false));
                    }
                    labels.Add(tile.Label);
                    planes.Add(RhinoConvert.ToPlane(tile));
                    steps.Add(tile.Step);
                }
                if (tiling.Report.Joints.Overlaps > 0)
                    AddRuntimeMessage(GH_RuntimeMessageLevel.Warning, tiling.Report.Joints.Overlaps + " contacts between tiles overlap (tile too large for the quads?).");
                if (tiling.Report.Cutting != null && tiling.Report.Cutting.Slivers > 0)
                    AddRuntimeMessage(GH_RuntimeMessageLevel.Remark, tiling.Report.Cutting.Slivers + " slivers were left out.");
                DA.SetDataList(0, full);
                DA.SetDataList(1, half);
                DA.SetDataList(2, cut);
                DA.SetDataList(3, labels);
                DA.SetDataList(4, planes);
                DA.SetDataList(5, steps);
                DA.SetData(6, tiling);
            });
        }

        public override BoundingBox ClippingBox { get { return previewBox; } }

        /// <summary>Full, half and cut tiles in their own colours (instead of the default preview).</summary>
        public override void DrawViewportMeshes(IGH_PreviewArgs args)
        {
            foreach (var item in preview)
            {
                DisplayMaterial material = item.Value == TileKind.Full ? FullMaterial : item.Value == TileKind.Half ? HalfMaterial : BoundaryMaterial;
                args.Display.DrawBrepShaded(item.Key, material);
            }
        }
    }
}

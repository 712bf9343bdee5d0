// The report of a tiling: counts, proof status, joint gaps and overlaps (before and after the
// fit), the fit's result, coverage.
using System;
using Grasshopper.Kernel;

namespace TilePattern.Gh
{
    public class TileReportComponent : ComponentBase
    {
        public TileReportComponent()
            : base("Tile Report", "TReport",
                "Reads the report of a tiling: tile counts, continuous joints, joint gaps and overlaps between neighbouring tiles (after the fit, and before it), the fit's result, coverage of the surface, proof status.",
                "3 Tiles")
        {
        }

        public override Guid ComponentGuid { get { return new Guid("3115c78b-3a2a-4165-babb-cbb85cce304f"); } }

        protected override System.Drawing.Bitmap Icon { get { return Icons.Load("TileReport"); } }

        public override GH_Exposure Exposure { get { return GH_Exposure.secondary; } }

        protected override void RegisterInputParams(GH_InputParamManager pManager)
        {
            pManager.AddGenericParameter("Tiling", "T", "Tiling from Tile Boxes", GH_ParamAccess.item);
        }

        protected override void RegisterOutputParams(GH_OutputParamManager pManager)
        {
            pManager.AddIntegerParameter("Full tiles", "F", "Tiles cut from full blanks (matched pairs)", GH_ParamAccess.item);
            pManager.AddIntegerParameter("Half tiles", "H", "Tiles cut from half blanks (unpaired quads)", GH_ParamAccess.item);
            pManager.AddIntegerParameter("Cut tiles", "C", "Tiles and pieces cut: full or half tiles cut to the boundary, and the filler pieces cut to the edge or to the holes the fit left", GH_ParamAccess.item);
            pManager.AddIntegerParameter("Continuous joints", "CJ", "Continuous joints left in the pattern", GH_ParamAccess.item);
            pManager.AddIntegerParameter("Contacts", "N", "Pairs of neighbouring tiles (joints measured)", GH_ParamAccess.item);
            pManager.AddNumberParameter("Min gap", "Gmin", "Narrowest joint between neighbouring tiles (negative: overlap)", GH_ParamAccess.item);
            pManager.AddNumberParameter("Max gap", "Gmax", "Widest joint between neighbouring tiles", GH_ParamAccess.item);
            pManager.AddNumberParameter("Mean gap", "Gmean", "Mean joint", GH_ParamAccess.item);
            pManager.AddNumberParameter("P95 deviation", "D95", "95th percentile of |gap - joint|", GH_ParamAccess.item);
            pManager.AddIntegerParameter("Overlaps", "O", "Pairs of tiles that overlap", GH_ParamAccess.item);
            pManager.AddNumberParameter("Coverage", "Cov", "Share of the surface under a kept tile or its half joint (when cut to a surface)", GH_ParamAccess.item);
            pManager.AddTextParameter("Status", "S", "optimal (proven), time_limit or feasible", GH_ParamAccess.item);
            pManager.AddTextParameter("JSON", "J", "The whole report as JSON", GH_ParamAccess.item);
            // Appended outputs keep the indices above.
            pManager.AddTextParameter("Fit", "Fit", "How the fit of the joints ended: converged, iteration_limit or time_limit (empty without the fit)", GH_ParamAccess.item);
            pManager.AddIntegerParameter("Fit cuts", "FC", "Tiles cut where they could not be fitted (labels C1, C2, ...)", GH_ParamAccess.item);
            pManager.AddNumberParameter("Within 2 mm", "W2", "Share of joints with |gap - joint| at most 2 mm", GH_ParamAccess.item);
            pManager.AddNumberParameter("Within 5 mm", "W5", "Share of joints with |gap - joint| at most 5 mm", GH_ParamAccess.item);
            pManager.AddNumberParameter("P95 deviation before fit", "D95b", "95th percentile of |gap - joint| as the paper places the tiles, before the fit (empty without the fit)", GH_ParamAccess.item);
            pManager.AddIntegerParameter("Tear cuts", "TC", "Pieces cut on site to the room inside the holes the fit opened (with Fit cuts, what the fit asks to be cut; empty without cutting to a surface)", GH_ParamAccess.item);
            pManager.AddIntegerParameter("Tear halves", "TH", "Whole half tiles laid in those holes where the room held one with its joints within half a joint (no cut on site; empty without cutting to a surface)", GH_ParamAccess.item);
        }

        protected override void SolveInstance(IGH_DataAccess DA)
        {
            Tiling tiling = Unwrap<Tiling>(DA, 0);
            if (tiling == null)
            {
                AddRuntimeMessage(GH_RuntimeMessageLevel.Error, "Tiling must come from a Tile Boxes component.");
                return;
            }
            Report r = tiling.Report;
            DA.SetData(0, r.FullTiles);
            DA.SetData(1, r.HalfTiles);
            DA.SetData(2, r.BoundaryTiles);
            DA.SetData(3, r.ContinuousJoints);
            DA.SetData(4, r.Joints.Contacts);
            DA.SetData(5, r.Joints.MinGap);
            DA.SetData(6, r.Joints.MaxGap);
            DA.SetData(7, r.Joints.MeanGap);
            DA.SetData(8, r.Joints.P95Deviation);
            DA.SetData(9, r.Joints.Overlaps);
            if (r.Cutting != null)
                DA.SetData(10, r.Cutting.Coverage);
            DA.SetData(11, r.StatusText);
            DA.SetData(12, r.Json);
            if (r.Fit != null)
                DA.SetData(13, r.Fit.StatusText);
            DA.SetData(14, r.Joints.FitCuts);
            DA.SetData(15, r.Joints.Within2Mm);
            DA.SetData(16, r.Joints.Within5Mm);
            if (r.Joints.BeforeFit != null)
                DA.SetData(17, r.Joints.BeforeFit.P95Deviation);
            if (r.Cutting != null)
            {
                DA.SetData(18, r.Cutting.TearCuts);
                DA.SetData(19, r.Cutting.TearHalves);
            }
            foreach (UserMessage message in UserMessage.ForJoints(r))
                Show(message);
            UserMessage laying = UserMessage.ForLaying(r);
            if (laying != null)
                Show(laying);
        }
    }
}

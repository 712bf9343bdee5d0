// The report of a tiling: counts, proof status, joint gaps and overlaps, coverage.
using System;
using Grasshopper.Kernel;

namespace TilePattern.Gh
{
    public class TileReportComponent : ComponentBase
    {
        public TileReportComponent()
            : base("Tile Report", "TReport",
                "Reads the report of a tiling: tile counts, continuous joints, joint gaps and overlaps between neighbouring tiles, coverage of the surface, proof status.",
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
            pManager.AddIntegerParameter("Cut tiles", "C", "Full or half tiles cut to the boundary", GH_ParamAccess.item);
            pManager.AddIntegerParameter("Continuous joints", "CJ", "Continuous joints left in the pattern", GH_ParamAccess.item);
            pManager.AddIntegerParameter("Contacts", "N", "Mesh edges between two different tiles", GH_ParamAccess.item);
            pManager.AddNumberParameter("Min gap", "Gmin", "Smallest gap between neighbouring tiles (negative: overlap)", GH_ParamAccess.item);
            pManager.AddNumberParameter("Max gap", "Gmax", "Largest gap between neighbouring tiles", GH_ParamAccess.item);
            pManager.AddNumberParameter("Mean gap", "Gmean", "Mean gap at the edge midpoints", GH_ParamAccess.item);
            pManager.AddNumberParameter("P95 deviation", "D95", "95th percentile of |gap - joint|", GH_ParamAccess.item);
            pManager.AddIntegerParameter("Overlaps", "O", "Contacts where the tiles overlap", GH_ParamAccess.item);
            pManager.AddNumberParameter("Coverage", "Cov", "Share of the surface under a kept tile or its half joint (when cut to a surface)", GH_ParamAccess.item);
            pManager.AddTextParameter("Status", "S", "optimal (proven), time_limit or feasible", GH_ParamAccess.item);
            pManager.AddTextParameter("JSON", "J", "The whole report as JSON", GH_ParamAccess.item);
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
            if (r.Joints.Overlaps > 0)
                AddRuntimeMessage(GH_RuntimeMessageLevel.Warning, r.Joints.Overlaps + " contacts overlap; the largest overlap is " + r.Joints.MaxOverlap + ".");
        }
    }
}

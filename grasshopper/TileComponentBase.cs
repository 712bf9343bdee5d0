// What the components that end in tiles share (Tile Boxes, Tile Surface): the tiles made into
// Breps on the worker, the seven tile outputs (registered and set in one place, so that both
// keep the same order), the messages about the joints and the report's warnings, and the
// preview with full, half, boundary-cut and fit-cut tiles in different colours.
using System;
using System.Collections.Generic;
using System.Drawing;
using System.Threading;
using Grasshopper.Kernel;
using Rhino.Display;
using Rhino.Geometry;

namespace TilePattern.Gh
{
    /// <summary>What a solve that ends in tiles makes on its worker: the tiling and its tiles as Breps.</summary>
    public sealed class TilesResult
    {
        /// <summary>The tiles and their report.</summary>
        public Tiling Tiling;

        /// <summary>Every tile as a Brep, with its label, frame, step, kind and deviation, in tile order.</summary>
        public TileOutputs<Brep> Outputs;

        /// <summary>Makes every tile of <paramref name="tiling"/> a Brep (on the worker thread),
        /// stopping when <paramref name="token"/> is cancelled.</summary>
        internal static TilesResult Make(Tiling tiling, double tolerance, CancellationToken token)
        {
            token.ThrowIfCancellationRequested();
            return new TilesResult
            {
                Tiling = tiling,
                Outputs = TileOutputs<Brep>.Build(tiling, (tile, pieces) =>
                {
                    token.ThrowIfCancellationRequested();
                    return RhinoConvert.ToBrep(tile, pieces, tolerance);
                }),
            };
        }
    }

    /// <summary>A background component whose first seven outputs are the tiles: Tiles, Labels,
    /// Planes, Steps, Kinds, Tiling and Deviation, parallel lists (item i of each is tile i);
    /// previewed by kind.</summary>
    public abstract class TileComponentBase<TResult> : BackgroundComponent<TResult> where TResult : class
    {
        static readonly DisplayMaterial FullMaterial = new DisplayMaterial(Color.FromArgb(200, 96, 48));
        static readonly DisplayMaterial HalfMaterial = new DisplayMaterial(Color.FromArgb(60, 120, 200));
        static readonly DisplayMaterial BoundaryMaterial = new DisplayMaterial(Color.FromArgb(230, 190, 40));
        static readonly DisplayMaterial FitCutMaterial = new DisplayMaterial(Color.FromArgb(200, 40, 120));

        // What the preview draws: the breps of the last solution, by kind (UI thread only).
        readonly List<KeyValuePair<Brep, string>> preview = new List<KeyValuePair<Brep, string>>();
        BoundingBox previewBox = BoundingBox.Empty;

        protected TileComponentBase(string name, string nickname, string description, string subcategory)
            : base(name, nickname, description, subcategory)
        {
        }

        /// <summary>Registers the seven tile outputs, at indices 0 to 6 (saved definitions wire
        /// by index: append anything else after them).</summary>
        protected static void RegisterTileOutputs(GH_OutputParamManager pManager)
        {
            pManager.AddBrepParameter("Tiles", "T", "Every tile as a solid, in tile order; a cut tile that splits is one Brep holding all its pieces; null where the solid could not be made (see the warnings)", GH_ParamAccess.list);
            pManager.AddTextParameter("Labels", "Lb", "Cut-list label of every tile (F, H, B1, ...), parallel to Tiles", GH_ParamAccess.list);
            pManager.AddPlaneParameter("Planes", "Pl", "Frame of every tile (origin, length axis x, width axis y), parallel to Tiles", GH_ParamAccess.list);
            pManager.AddIntegerParameter("Steps", "N", "Laying order of every tile, from 0, parallel to Tiles", GH_ParamAccess.list);
            pManager.AddTextParameter("Kinds", "K", "full, half, boundary (cut to the boundary) or fit_cut (cut where it could not be fitted), parallel to Tiles", GH_ParamAccess.list);
            pManager.AddGenericParameter("Tiling", "Tg", "All tiles and the report, for Tile Report", GH_ParamAccess.item);
            // Appended outputs keep the indices above.
            pManager.AddNumberParameter("Deviation", "D", "Worst joint of every tile: the largest |gap - joint| to its neighbours, in model units, parallel to Tiles (e.g. through Bounds and Gradient into Custom Preview to colour the tiles by their joints)", GH_ParamAccess.list);
        }

        protected override void BeforeSolveInstance()
        {
            preview.Clear();
            previewBox = BoundingBox.Empty;
            base.BeforeSolveInstance();
        }

        /// <summary>Sets outputs 0 to 6 from <paramref name="result"/>, adds its tiles to the
        /// preview and shows what the solids, the joints and the report's checks say (on the UI
        /// thread).</summary>
        protected void SetTileOutputs(IGH_DataAccess DA, TilesResult result)
        {
            TileOutputs<Brep> tiles = result.Outputs;
            foreach (string warning in tiles.Warnings)
                AddRuntimeMessage(GH_RuntimeMessageLevel.Warning, "The solid of " + warning);
            var planes = new List<Plane>(tiles.Count);
            for (int i = 0; i < tiles.Count; i++)
            {
                planes.Add(RhinoConvert.ToPlane(tiles.Frames[i]));
                Brep brep = tiles.Geometry[i];
                if (brep != null)
                {
                    preview.Add(new KeyValuePair<Brep, string>(brep, tiles.Kinds[i]));
                    previewBox.Union(brep.GetBoundingBox(false));
                }
            }
            Report report = result.Tiling.Report;
            foreach (UserMessage message in UserMessage.ForJoints(report))
                Show(message);
            UserMessage laying = UserMessage.ForLaying(report);
            if (laying != null)
                Show(laying);
            // The library's checks (closed or split surface, tile shape, coverage, dropped tiles
            // and slivers, no support, ...): each stays visible on the component.
            if (report.Warnings != null)
                foreach (TilingWarning warning in report.Warnings)
                    AddRuntimeMessage(GH_RuntimeMessageLevel.Warning, warning.ToString());
            DA.SetDataList(0, tiles.Geometry);
            DA.SetDataList(1, tiles.Labels);
            DA.SetDataList(2, planes);
            DA.SetDataList(3, tiles.Steps);
            DA.SetDataList(4, tiles.Kinds);
            DA.SetData(5, result.Tiling);
            DA.SetDataList(6, tiles.Deviations);
        }

        /// <summary>The box of the previewed tiles.</summary>
        public override BoundingBox ClippingBox { get { return previewBox; } }

        /// <summary>Full, half, boundary-cut and fit-cut tiles in their own colours (instead of
        /// the default preview).</summary>
        public override void DrawViewportMeshes(IGH_PreviewArgs args)
        {
            foreach (var item in preview)
            {
                DisplayMaterial material = item.Value == "full" ? FullMaterial : item.Value == "half" ? HalfMaterial
                    : item.Value == "fit_cut" ? FitCutMaterial : BoundaryMaterial;
                args.Display.DrawBrepShaded(item.Key, material);
            }
        }
    }
}

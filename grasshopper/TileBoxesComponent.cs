// Stage 3: a box per matched pair, a half tile per unpaired quad, moved by the fit stage so
// that the joints come close to the mortar joint (what cannot fit is cut), boundary tiles cut
// to the surface; one list of tiles parallel to their labels, frames, laying steps, kinds and
// joint deviations; previewed with full, half, boundary-cut and fit-cut tiles in different
// colours.
using System;
using System.Collections.Generic;
using System.Drawing;
using Grasshopper.Kernel;
using Rhino.Display;
using Rhino.Geometry;

namespace TilePattern.Gh
{
    /// <summary>What a Tile Boxes solve makes on its worker: the tiling and its tiles as Breps.</summary>
    public sealed class TileBoxesResult
    {
        public Tiling Tiling;
        public TileOutputs<Brep> Outputs;
    }

    public class TileBoxesComponent : BackgroundComponent<TileBoxesResult>
    {
        static readonly DisplayMaterial FullMaterial = new DisplayMaterial(Color.FromArgb(200, 96, 48));
        static readonly DisplayMaterial HalfMaterial = new DisplayMaterial(Color.FromArgb(60, 120, 200));
        static readonly DisplayMaterial BoundaryMaterial = new DisplayMaterial(Color.FromArgb(230, 190, 40));
        static readonly DisplayMaterial FitCutMaterial = new DisplayMaterial(Color.FromArgb(200, 40, 120));

        // What the preview draws: the breps of the last solution, by kind (UI thread only).
        readonly List<KeyValuePair<Brep, string>> preview = new List<KeyValuePair<Brep, string>>();
        BoundingBox previewBox = BoundingBox.Empty;

        public TileBoxesComponent()
            : base("Tile Boxes", "TBoxes",
                "Builds the tiles of a pattern: a box per matched pair (full tile), a half tile per unpaired quad, moved on the surface so that every joint comes close to the mortar joint (the fit; what cannot fit is cut), cut to the surface's boundary (every piece); one list of tiles with their cut-list labels, frames, laying order, kinds and joint deviations. Preview: full tiles terracotta, half tiles blue, tiles cut to the boundary yellow, tiles cut to fit magenta. Solves in the background; right-click to cancel.",
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
            pManager.AddNumberParameter("Length", "L", "Tile length in model units (default: 280 mm in the document's units)", GH_ParamAccess.item);
            pManager.AddNumberParameter("Width", "W", "Tile width in model units (default: 140 mm)", GH_ParamAccess.item);
            pManager.AddNumberParameter("Thickness", "T", "Tile thickness in model units (default: 15 mm)", GH_ParamAccess.item);
            pManager.AddNumberParameter("Joint", "J", "Mortar joint in model units (default: 10 mm)", GH_ParamAccess.item);
            pManager.AddMeshParameter("Surface", "S", "Optional: the input surface; tiles are cut to its boundary (default: the quad mesh's boundary)", GH_ParamAccess.item);
            // Appended inputs keep the indices above (saved definitions wire by index).
            pManager.AddBooleanParameter("Fit", "F", "Move the tiles on the surface so that every joint comes close to the mortar joint, keeping the bond, and cut what cannot fit (default true); false keeps the paper's placement", GH_ParamAccess.item, true);
            pManager.AddBooleanParameter("Creases", "Cr", "Cut the tiles to the Surface's creases (where its faces turn sharply: a groin vault's groins, a fold), half a joint short on each side, and keep every tile on its own side (default true); give Quad Remesh the same", GH_ParamAccess.item, true);
            for (int i = 1; i <= 6; i++)
                pManager[i].Optional = true;
            pManager[8].Optional = true;
        }

        protected override void RegisterOutputParams(GH_OutputParamManager pManager)
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

        protected override void SolveInstance(IGH_DataAccess DA)
        {
            Pattern pattern = Unwrap<Pattern>(DA, 0);
            if (pattern == null)
            {
                AddRuntimeMessage(GH_RuntimeMessageLevel.Error, "Pattern must come from a Tile Pattern component.");
                return;
            }
            TileDefaults defaults = Defaults();
            Mesh quadsMesh = null, surfaceMesh = null;
            double length = defaults.Length, width = defaults.Width, thickness = defaults.Thickness, joint = defaults.Joint;
            bool hasQuads = DA.GetData(1, ref quadsMesh) && quadsMesh != null;
            DA.GetData(2, ref length);
            DA.GetData(3, ref width);
            DA.GetData(4, ref thickness);
            DA.GetData(5, ref joint);
            bool hasSurface = DA.GetData(6, ref surfaceMesh) && surfaceMesh != null;
            bool fit = true;
            DA.GetData(7, ref fit);
            bool creases = true;
            DA.GetData(8, ref creases);
            double tolerance = Tolerance();

            PolyMesh quads = null, surface = null;
            int turnedQuads = 0, turnedSurface = 0;
            if (!Run(() =>
            {
                quads = hasQuads ? RhinoConvert.ToPolyMesh(quadsMesh, out turnedQuads) : null;
                surface = hasSurface ? RhinoConvert.ToPolyMesh(surfaceMesh, out turnedSurface) : null;
            }))
                return;
            WarnTurned(turnedQuads, "quad");
            WarnTurned(turnedSurface, "surface");
            // UnitsPerMm from the document's units: the report's shares of joints within 2 and 5 mm.
            var options = new TileOptions { Length = length, Width = width, Thickness = thickness, Joint = joint, Fit = fit, UnitsPerMm = defaults.UnitsPerMm, Creases = creases };
            // The pattern by identity and by content (identity hashes alone may collide).
            var flatPairs = new List<int>(2 * pattern.Pairs.Length);
            foreach (FacePair pair in pattern.Pairs)
            {
                flatPairs.Add(pair.A);
                flatPairs.Add(pair.B);
            }
            var key = new InputKey().AddIdentity(pattern).Add(pattern.QuadMesh).Add(flatPairs).Add(pattern.Unpaired).Add(quads).Add(surface).Add(length).Add(width).Add(thickness).Add(joint).Add(tolerance).Add(fit).Add(options.UnitsPerMm);
            TileBoxesResult result = Solve(DA, key, (token, progress) =>
            {
                // The fit reports its progress and stops when the job is cancelled.
                Tiling tiling = quads != null ? TilePatternEngine.Tiles(quads, pattern, options, surface, progress, token)
                    : TilePatternEngine.Tiles(pattern, options, surface, progress, token);
                token.ThrowIfCancellationRequested();
                return new TileBoxesResult
                {
                    Tiling = tiling,
                    Outputs = TileOutputs<Brep>.Build(tiling, (tile, pieces) =>
                    {
                        token.ThrowIfCancellationRequested();
                        return RhinoConvert.ToBrep(tile, pieces, tolerance);
                    }),
                };
            });
            if (result == null)
                return;

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

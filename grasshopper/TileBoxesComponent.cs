// Stage 3: a box per matched pair, a half tile per unpaired quad, moved by the fit stage so
// that the joints come close to the mortar joint (what cannot fit is cut), boundary tiles cut
// to the surface; one list of tiles parallel to their labels, frames, laying steps, kinds and
// joint deviations; previewed with full, half, boundary-cut and fit-cut tiles in different
// colours.
using System;
using System.Collections.Generic;
using System.Drawing;
using Grasshopper.Kernel;
using Rhino.Geometry;

namespace TilePattern.Gh
{
    public class TileBoxesComponent : TileComponentBase<TilesResult>
    {
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
            RegisterTileOutputs(pManager);
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
            int[] joined;
            if (hasQuads && !ReadMesh(quadsMesh, "quad", out quads, out joined))
                return;
            if (hasSurface && !ReadMesh(surfaceMesh, "surface", out surface, out joined))
                return;
            // UnitsPerMm from the document's units: the report's shares of joints within 2 and 5 mm.
            var options = new TileOptions { Length = length, Width = width, Thickness = thickness, Joint = joint, Fit = fit, UnitsPerMm = defaults.UnitsPerMm, Creases = creases };
            // The pattern by identity and by content (identity hashes alone may collide).
            var flatPairs = new List<int>(2 * pattern.Pairs.Length);
            foreach (FacePair pair in pattern.Pairs)
            {
                flatPairs.Add(pair.A);
                flatPairs.Add(pair.B);
            }
            var key = new InputKey().AddIdentity(pattern).Add(pattern.QuadMesh).Add(flatPairs).Add(pattern.Unpaired).Add(quads).Add(surface).Add(length).Add(width).Add(thickness).Add(joint).Add(tolerance).Add(fit).Add(options.UnitsPerMm).Add(creases);
            TilesResult result = Solve(DA, key, (token, progress) =>
                // The fit reports its progress and stops when the job is cancelled.
                TilesResult.Make(quads != null ? TilePatternEngine.Tiles(quads, pattern, options, surface, progress, token)
                    : TilePatternEngine.Tiles(pattern, options, surface, progress, token), tolerance, token));
            if (result != null)
                SetTileOutputs(DA, result);
        }
    }
}

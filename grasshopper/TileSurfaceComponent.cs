// The three stages in one, as the command line's run: a surface mesh to fitted tiles cut to its
// boundary, on up to six quad meshes (the field's renormalisation strength, a smooth field, twice
// and half the strength, the smooth field's quads laid out for level courses, the smooth field free
// of the boundary), keeping the tiles that fit best (TilePatternEngine.Run).
using System;
using System.Collections.Generic;
using Grasshopper.Kernel;
using Grasshopper.Kernel.Parameters;
using Rhino.Geometry;

namespace TilePattern.Gh
{
    /// <summary>What a Tile Surface solve makes on its worker: the kept quads, pattern and tiles,
    /// and the tiles as Breps.</summary>
    public sealed class TileSurfaceResult
    {
        /// <summary>The kept quad mesh, pattern and tiles (the report lists every try).</summary>
        public RunResult Run;

        /// <summary>The kept tiles as Breps.</summary>
        public TilesResult Tiles;
    }

    /// <summary>Tile Surface: the three stages in one step with tries (TilePatternEngine.Run);
    /// outputs 0 to 6 as Tile Boxes', then the kept quad mesh and pattern.</summary>
    public class TileSurfaceComponent : TileComponentBase<TileSurfaceResult>
    {
        public TileSurfaceComponent()
            : base("Tile Surface", "TSurface",
                "Tiles a surface mesh in one step, as the command line's run: quad remeshing, the pattern and the tiles with the fit of the joints, cut to the surface's boundary, on up to six quad meshes of the surface (Tries), keeping the tiles that fit best (joints not flagged wide first, then cuts within 1 % of the tiles, then the fewest cuts and the closest joints); the same outputs as Tile Boxes, and the kept quad mesh and pattern. A remark says which try was kept. Solves in the background; right-click to cancel.",
                "3 Tiles")
        {
        }

        public override Guid ComponentGuid { get { return new Guid("06d6afc0-41d9-4888-aa3c-315f4e6778f4"); } }

        protected override System.Drawing.Bitmap Icon { get { return Icons.Load("TileSurface"); } }

        public override GH_Exposure Exposure { get { return GH_Exposure.primary; } }

        protected override void RegisterInputParams(GH_InputParamManager pManager)
        {
            pManager.AddMeshParameter("Mesh", "M", "The shell's surface: a triangle, quad or mixed mesh, in model units; the tiles are cut to its boundary", GH_ParamAccess.item);
            pManager.AddNumberParameter("Length", "L", "Tile length in model units (default: 280 mm in the document's units)", GH_ParamAccess.item);
            pManager.AddNumberParameter("Width", "W", "Tile width in model units (default: 140 mm)", GH_ParamAccess.item);
            pManager.AddNumberParameter("Thickness", "T", "Tile thickness in model units (default: 15 mm)", GH_ParamAccess.item);
            pManager.AddNumberParameter("Joint", "J", "Mortar joint in model units (default: 10 mm)", GH_ParamAccess.item);
            pManager.AddIntegerParameter("Bond", "B", "0 = stack (maximum matching), 1 = staggered, 2 = running bond, 3 = herringbone, 4 = basket weave (3 and 4 lay tiles both ways: always in free courses)", GH_ParamAccess.item, (int)Bond.Staggered);
            pManager.AddIntegerParameter("Courses", "C", "1 = level: every tile along level courses (horizontal in the world's z) on quads of max((length + joint) / 2, width + joint), which the fit closes far better (default); 0 = free: tiles either way across quads of (length + joint) / 2 (the paper's model)", GH_ParamAccess.item, (int)Courses.Level);
            pManager.AddBooleanParameter("Fit", "F", "Move the tiles on the surface so that every joint comes close to the mortar joint, keeping the bond, and cut what cannot fit (default true); false keeps the paper's placement", GH_ParamAccess.item, true);
            pManager.AddIntegerParameter("Tries", "Tr", "How many quad meshes to lay tiles on, keeping the tiles that fit best: 0 = automatic (all on a surface of at most 10,000 quads, else 1; default), or 1 to 6 (renormalisation 0.5, then a smooth field that follows neither the curvature nor anything else, made only without a direction, angle, designer's field or guides, then 1, then 0.25, then the smooth field's quads laid out for level courses, half a tile and a joint along them, made only in level courses, then the smooth field free of the boundary, its rows cut to curved edges instead of following them, made only where the first try follows an edge with corners). 1 gives what Quad Remesh, Tile Pattern and Tile Boxes give one by one", GH_ParamAccess.item, 0);
            pManager.AddNumberParameter("Time limit", "TL", "Seconds of the pattern stage (default 10; a later try has at most 10); when a try's pattern stage or fit reaches its time limit no further try is made, except after the first try's pattern stage with a limit over 10", GH_ParamAccess.item, 10.0);
            pManager.AddBooleanParameter("Creases", "Cr", "Split the mesh where its faces turn sharply (a groin vault's groins, a fold): each part gets quads of its own and the tiles are cut to the creases, half a joint short on each side (default true)", GH_ParamAccess.item, true);
            pManager.AddIntegerParameter("Excluded", "X", "Optional: faces of Mesh to leave out (openings, areas laid by hand): each quad whose closest face of Mesh is one gets no tile and no filler, and its area is left out of the coverage", GH_ParamAccess.list);
            pManager.AddIntegerParameter("Zones", "Z", "Optional: a bond per face of Mesh (not of the quads), in face order (0 to 4 as Bond, -1 = the Bond input); each quad takes the zone of the face of Mesh closest to it. Empty: every face in Bond. A herringbone or basket-weave zone lays in free courses", GH_ParamAccess.list);
            for (int i = 1; i <= 4; i++)
                pManager[i].Optional = true;
            pManager[11].Optional = true;
            pManager[12].Optional = true;
            NameBonds((Param_Integer)pManager[5]);
            NameCourses((Param_Integer)pManager[6]);
            var tries = (Param_Integer)pManager[8];
            tries.AddNamedValue("Automatic", 0);
            tries.AddNamedValue("One try", 1);
            tries.AddNamedValue("Two tries", 2);
            tries.AddNamedValue("Three tries", 3);
            tries.AddNamedValue("Four tries", 4);
            tries.AddNamedValue("Five tries", 5);
            tries.AddNamedValue("Six tries", 6);
        }

        protected override void RegisterOutputParams(GH_OutputParamManager pManager)
        {
            RegisterTileOutputs(pManager);
            pManager.AddMeshParameter("Quad mesh", "Q", "The quad mesh the kept tiles were laid on", GH_ParamAccess.item);
            pManager.AddGenericParameter("Pattern", "P", "The kept pattern (solved on Quad mesh), for Tile Boxes", GH_ParamAccess.item);
        }

        protected override void SolveInstance(IGH_DataAccess DA)
        {
            Mesh mesh = null;
            if (!DA.GetData(0, ref mesh) || mesh == null)
                return;
            TileDefaults defaults = Defaults();
            double length = defaults.Length, width = defaults.Width, thickness = defaults.Thickness, joint = defaults.Joint, timeLimit = 10.0;
            int bond = (int)Bond.Staggered, courses = (int)Courses.Level, tries = 0;
            bool fit = true, creases = true;
            DA.GetData(1, ref length);
            DA.GetData(2, ref width);
            DA.GetData(3, ref thickness);
            DA.GetData(4, ref joint);
            DA.GetData(5, ref bond);
            DA.GetData(6, ref courses);
            DA.GetData(7, ref fit);
            DA.GetData(8, ref tries);
            DA.GetData(9, ref timeLimit);
            DA.GetData(10, ref creases);
            var excluded = new List<int>();
            var zones = new List<int>();
            DA.GetDataList(11, excluded);
            DA.GetDataList(12, zones);
            if (!CheckBond(bond) || !CheckCourses(courses))
                return;
            Bond?[] zoneBonds = ZoneBonds(zones);
            if (zoneBonds == null)
                return;
            if (tries < 0 || tries > RunOptions.MaxTries)
            {
                AddRuntimeMessage(GH_RuntimeMessageLevel.Error, "Tries is 0 (automatic) or 1 to " + RunOptions.MaxTries + ", not " + tries + ".");
                return;
            }
            // The quads are then those of free courses too, as the command line's run makes them.
            courses = CoursesFor(bond, zones, courses);
            // The quads as Quad Remesh makes them for these courses; UnitsPerMm from the
            // document's units, for the report's shares of joints within 2 and 5 mm.
            var remesh = new RemeshOptions { TargetEdge = TileOptions.QuadEdgeOf(length, width, joint, (Courses)courses), Creases = creases };
            var pattern = new PatternOptions { Bond = (Bond)bond, TimeLimitSeconds = timeLimit, Courses = (Courses)courses };
            if (zones.Count > 0)
                pattern.Zones = zoneBonds;
            foreach (int face in excluded)
                pattern.ExcludedFaces.Add(face);
            var tile = new TileOptions { Length = length, Width = width, Thickness = thickness, Joint = joint, Fit = fit, UnitsPerMm = defaults.UnitsPerMm, Creases = creases };
            var run = new RunOptions { Tries = tries };
            double tolerance = Tolerance();
            PolyMesh surface;
            int[] joined;
            if (!ReadMesh(mesh, "surface", out surface, out joined))
                return;
            var key = new InputKey().Add(surface).Add(length).Add(width).Add(thickness).Add(joint).Add(bond).Add(courses).Add(fit).Add(tries)
                .Add(timeLimit).Add(creases).Add(tolerance).Add(tile.UnitsPerMm).Add(excluded).Add(zones);
            TileSurfaceResult result = Solve(DA, key, (token, progress) =>
            {
                // The whole run reports its progress (each try an equal share) and stops when
                // the job is cancelled.
                RunResult found = TilePatternEngine.Run(surface, remesh, pattern, tile, run, progress, token);
                try
                {
                    return new TileSurfaceResult { Run = found, Tiles = TilesResult.Make(found.Tiling, tolerance, token) };
                }
                catch
                {
                    found.Dispose();
                    throw;
                }
            });
            if (result == null)
                return;

            SetTileOutputs(DA, result.Tiles);
            Show(UserMessage.ForTries(result.Run.Tiling.Report));
            Pattern kept = result.Run.Pattern;
            if (kept.Status != SolveStatus.Optimal)
                AddRuntimeMessage(GH_RuntimeMessageLevel.Remark, "The kept pattern is not proven optimal (" + result.Run.Tiling.Report.StatusText + "): gap "
                    + (100 * kept.Gap).ToString("0.##", System.Globalization.CultureInfo.InvariantCulture) + " %.");
            DA.SetData(7, RhinoConvert.ToRhinoMesh(result.Run.Quads));
            // Not disposed here: the pattern travels downstream; its SafeHandles free the native
            // memory (announced to the GC) once Grasshopper lets go of it.
            DA.SetData(8, kept);
        }
    }
}

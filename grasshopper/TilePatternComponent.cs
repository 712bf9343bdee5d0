// Stage 2: matches adjacent quads into tiles (the paper's programs on CBC).
using System;
using System.Collections.Generic;
using System.Linq;
using Grasshopper;
using Grasshopper.Kernel;
using Grasshopper.Kernel.Data;
using Grasshopper.Kernel.Parameters;
using Rhino.Geometry;

namespace TilePattern.Gh
{
    public class TilePatternComponent : BackgroundComponent<Pattern>
    {
        public TilePatternComponent()
            : base("Tile Pattern", "TPattern",
                "Matches adjacent quads into tiles: stack bond (maximum matching), staggered bond (fewest continuous joints), running bond, herringbone or basket weave, solved to a proven optimum or until the time limit; tiles along level courses (default, they fit far better) or either way. Solves in the background; right-click to cancel.",
                "2 Pattern")
        {
        }

        public override Guid ComponentGuid { get { return new Guid("3bee156c-5311-417e-a925-2500ee92c17c"); } }

        protected override System.Drawing.Bitmap Icon { get { return Icons.Load("TilePattern"); } }

        public override GH_Exposure Exposure { get { return GH_Exposure.primary; } }

        protected override void RegisterInputParams(GH_InputParamManager pManager)
        {
            pManager.AddMeshParameter("Quad mesh", "Q", "Quad mesh (from Quad Remesh)", GH_ParamAccess.item);
            pManager.AddIntegerParameter("Bond", "B", "0 = stack (maximum matching), 1 = staggered, 2 = running bond, 3 = herringbone, 4 = basket weave (3 and 4 lay tiles both ways: always in free courses)", GH_ParamAccess.item, 1);
            pManager.AddNumberParameter("Weight", "W", "Staggered: penalty per continuous joint; running bond: reward per shifted pair; herringbone: penalty per continuous joint or end-to-end pair; basket weave: penalty per shifted, end-to-end or one-course-apart pair", GH_ParamAccess.item, 0.5);
            pManager.AddNumberParameter("Time limit", "T", "Seconds; 0 returns the greedy start at once", GH_ParamAccess.item, 10.0);
            pManager.AddIntegerParameter("Forced pairs", "F", "Optional: face indices a0, b0, a1, b1, ... of adjacent quads that must form tiles", GH_ParamAccess.list);
            pManager.AddIntegerParameter("Excluded", "X", "Optional: faces that take part in no tile (openings, areas laid by hand)", GH_ParamAccess.list);
            // Appended inputs keep the indices above (saved definitions wire by index).
            pManager.AddIntegerParameter("Courses", "C", "1 = level: every tile along level courses (horizontal in the world's z), which the fit closes far better (default); 0 = free: tiles either way across any quad (the paper's model). For level courses remesh with quads of max((length + joint) / 2, width + joint) (Quad Remesh's Courses input)", GH_ParamAccess.item, (int)Courses.Level);
            pManager.AddNumberParameter("Gap", "Gp", "Optional: stop once (bound - objective) / bound is at most this relative gap, like a MIP solver's (0 = prove optimality or reach the time limit, default; 0.01 = within 1 %)", GH_ParamAccess.item, 0.0);
            pManager.AddIntegerParameter("Zones", "Z", "Optional: a bond per face of the quad mesh, in face order (0 to 4 as Bond, -1 = the Bond input), e.g. a band of herringbone in a staggered vault; every zone at Weight. Empty: every face in Bond. A herringbone or basket-weave zone lays in free courses", GH_ParamAccess.list);
            pManager[4].Optional = true;
            pManager[5].Optional = true;
            pManager[7].Optional = true;
            pManager[8].Optional = true;
            NameBonds((Param_Integer)pManager[1]);
            NameCourses((Param_Integer)pManager[6]);
        }

        protected override void RegisterOutputParams(GH_OutputParamManager pManager)
        {
            pManager.AddGenericParameter("Pattern", "P", "The solved pattern, for Tile Boxes", GH_ParamAccess.item);
            pManager.AddIntegerParameter("Pairs", "Pr", "Matched face pairs, one branch per tile: {input path; item; tile}", GH_ParamAccess.tree);
            pManager.AddIntegerParameter("Unpaired", "U", "Quads in no pair: each becomes a half tile", GH_ParamAccess.list);
            pManager.AddTextParameter("Status", "S", "optimal (proven), time_limit or feasible", GH_ParamAccess.item);
            pManager.AddNumberParameter("Objective", "O", "Objective of the pattern", GH_ParamAccess.item);
            pManager.AddNumberParameter("Bound", "Bd", "Proven upper bound on the objective", GH_ParamAccess.item);
            pManager.AddNumberParameter("Gap", "G", "(bound - objective) / max(bound, 1)", GH_ParamAccess.item);
            pManager.AddIntegerParameter("Continuous joints", "CJ", "Continuous joints left in the pattern", GH_ParamAccess.item);
        }

        protected override void SolveInstance(IGH_DataAccess DA)
        {
            Mesh mesh = null;
            int bond = 1, courses = (int)Courses.Level;
            double weight = 0.5, timeLimit = 10.0, gap = 0.0;
            var forced = new List<int>();
            var excluded = new List<int>();
            var zones = new List<int>();
            if (!DA.GetData(0, ref mesh) || mesh == null)
                return;
            DA.GetData(1, ref bond);
            DA.GetData(2, ref weight);
            DA.GetData(3, ref timeLimit);
            DA.GetDataList(4, forced);
            DA.GetDataList(5, excluded);
            DA.GetData(6, ref courses);
            DA.GetData(7, ref gap);
            DA.GetDataList(8, zones);
            if (forced.Count % 2 != 0)
            {
                AddRuntimeMessage(GH_RuntimeMessageLevel.Error, "Forced pairs needs an even number of face indices (a0, b0, a1, b1, ...).");
                return;
            }
            if (!CheckBond(bond) || !CheckCourses(courses))
                return;
            Bond?[] zoneBonds = ZoneBonds(zones);
            if (zoneBonds == null)
                return;
            courses = CoursesFor(bond, zones, courses);
            var options = new PatternOptions { Bond = (Bond)bond, Weight = weight, TimeLimitSeconds = timeLimit, Gap = gap, Courses = (Courses)courses };
            if (zones.Count > 0)
                options.Zones = zoneBonds;
            for (int k = 0; k < forced.Count; k += 2)
                options.ForcedPairs.Add(new FacePair(forced[k], forced[k + 1]));
            foreach (int face in excluded)
                options.ExcludedFaces.Add(face);
            PolyMesh quads;
            int[] joined;
            if (!ReadMesh(mesh, "quad", out quads, out joined))
                return;
            var key = new InputKey().Add(quads).Add(bond).Add(weight).Add(timeLimit).Add(forced).Add(excluded).Add(courses).Add(gap).Add(zones);
            // Not disposed here: the pattern travels downstream; its SafeHandles free the native
            // memory (announced to the GC) once Grasshopper lets go of it.
            Pattern pattern = Solve(DA, key, (token, progress) => TilePatternEngine.Match(quads, options, progress, token));
            if (pattern == null)
                return;

            // One branch per tile under this solve's own target (path and index), so that the
            // pairs of several meshes never share a branch.
            int[][] paths = TreePaths.Branches(DA.ParameterTargetPath(1).Indices, DA.ParameterTargetIndex(1), pattern.Pairs.Length);
            var pairs = new DataTree<int>();
            for (int i = 0; i < pattern.Pairs.Length; i++)
                pairs.AddRange(new[] { pattern.Pairs[i].A, pattern.Pairs[i].B }, new GH_Path(paths[i]));
            string status = pattern.Status == SolveStatus.Optimal ? "optimal" : pattern.Status == SolveStatus.TimeLimit ? "time_limit" : "feasible";
            if (pattern.Status != SolveStatus.Optimal)
                AddRuntimeMessage(GH_RuntimeMessageLevel.Remark, "Not proven optimal (" + status + "): gap " + (100 * pattern.Gap).ToString("0.##") + " %.");
            if (pattern.NonQuadCount > 0)
                AddRuntimeMessage(GH_RuntimeMessageLevel.Warning, pattern.NonQuadCount + " faces are not quads and get no tile.");
            DA.SetData(0, pattern);
            DA.SetDataTree(1, pairs);
            DA.SetDataList(2, pattern.Unpaired);
            DA.SetData(3, status);
            DA.SetData(4, pattern.Objective);
            DA.SetData(5, pattern.Bound);
            DA.SetData(6, pattern.Gap);
            DA.SetData(7, pattern.ContinuousJoints);
        }
    }
}

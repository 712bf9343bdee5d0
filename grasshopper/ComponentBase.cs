// What every TilePattern component shares: the ribbon tab, error reporting (the wording lives
// in the wrapper, TilePattern.UserMessage), the document's units and tolerance, finding the
// native library, and solving in the background.
using System;
using System.Collections.Generic;
using System.Linq;
using System.Threading;
using System.Windows.Forms;
using Grasshopper.Kernel;
using Grasshopper.Kernel.Parameters;
using Rhino.Geometry;

namespace TilePattern.Gh
{
    public abstract class ComponentBase : GH_Component
    {
        /// <summary>The ribbon tab of every TilePattern component. (Not named Category: that
        /// would hide GH_InstanceDescription.Category, warning CS0108.)</summary>
        internal const string Tab = "TilePattern";

        protected ComponentBase(string name, string nickname, string description, string subcategory)
            : base(name, nickname, description, Tab, subcategory)
        {
        }

        /// <summary>Shows a message from the wrapper as a runtime message.</summary>
        protected void Show(UserMessage message)
        {
            GH_RuntimeMessageLevel level = message.Level == MessageLevel.Error ? GH_RuntimeMessageLevel.Error
                : message.Level == MessageLevel.Warning ? GH_RuntimeMessageLevel.Warning : GH_RuntimeMessageLevel.Remark;
            AddRuntimeMessage(level, message.Text);
        }

        /// <summary>Says, as the command line's warning normals_unified does, that faces of an input
        /// mesh were turned to agree with their neighbours (on a copy).</summary>
        protected void WarnTurned(int turnedFaces, string input)
        {
            if (turnedFaces > 0)
                AddRuntimeMessage(GH_RuntimeMessageLevel.Warning,
                    "[normals_unified] " + turnedFaces + " faces of the " + input + " mesh did not face the same side as their neighbours and were turned over (on a copy); " +
                    "tiles are laid on the side the normals point to, so unify the normals in Rhino (UnifyMeshNormals, then Flip if needed) to choose it yourself.");
        }

        /// <summary>A Rhino mesh as a PolyMesh (<see cref="RhinoConvert.ToPolyMesh(Mesh, out int, out int[], out string)"/>),
        /// with the messages of what was done to it: faces turned, vertices at one place
        /// joined (a remark) or left apart (a warning, why). <paramref name="vertexSource"/>
        /// is each joined vertex's first vertex of <paramref name="mesh"/>, null when none
        /// was joined. False, with an error, when the conversion failed.</summary>
        protected bool ReadMesh(Mesh mesh, string input, out PolyMesh polyMesh, out int[] vertexSource)
        {
            PolyMesh converted = null;
            int turned = 0;
            int[] joined = null;
            string apart = null;
            bool read = Run(() => converted = RhinoConvert.ToPolyMesh(mesh, out turned, out joined, out apart));
            polyMesh = converted;
            vertexSource = joined;
            if (!read)
                return false;
            WarnTurned(turned, input);
            if (apart != null)
                AddRuntimeMessage(GH_RuntimeMessageLevel.Warning,
                    "[vertices_welded] The " + input + " mesh has vertices at the same places that its faces do not share, left apart: " + apart +
                    ". Its pieces are remeshed and cut apart; weld the mesh in Rhino (Weld, or JoinMesh then Weld) after cleaning it.");
            if (joined != null)
                AddRuntimeMessage(GH_RuntimeMessageLevel.Remark,
                    "[vertices_welded] The " + input + " mesh's faces did not share their vertices along their seams (a polysurface meshed face by face): " +
                    (mesh.Vertices.Count - joined.Length) + " vertices at the same places as others were joined (on a copy), so that it is one surface, not pieces remeshed and cut apart; its faces keep their numbers.");
            return true;
        }

        /// <summary>Runs a step on the UI thread, turning a failure into a runtime message.</summary>
        protected bool Run(Action step)
        {
            try
            {
                step();
                return true;
            }
            catch (Exception e)
            {
                Show(UserMessage.For(e));
                return false;
            }
        }

        /// <summary>The tile defaults (280 x 140 x 15 mm, joint 10 mm) in the active document's
        /// units; read on the UI thread. Without a document or with units of no fixed length they
        /// are millimetres, and a remark says so.</summary>
        protected TileDefaults Defaults()
        {
            Rhino.RhinoDoc doc = Rhino.RhinoDoc.ActiveDoc;
            TileDefaults defaults = TileDefaults.For(doc == null ? null : doc.ModelUnitSystem.ToString());
            if (!defaults.UnitsKnown)
                AddRuntimeMessage(GH_RuntimeMessageLevel.Remark, "The document's units have no fixed length: the default tile sizes are taken as millimetres.");
            return defaults;
        }

        /// <summary>The document's absolute tolerance (read on the UI thread).</summary>
        protected static double Tolerance()
        {
            double tolerance = DocumentTolerance();
            return tolerance > 0 ? tolerance : 1e-6;
        }

        /// <summary>Names the values of a Bond input (0 to 4).</summary>
        protected static void NameBonds(Param_Integer bond)
        {
            bond.AddNamedValue("Stack", (int)Bond.Stack);
            bond.AddNamedValue("Staggered", (int)Bond.Staggered);
            bond.AddNamedValue("Running bond", (int)Bond.RunningBond);
            bond.AddNamedValue("Herringbone", (int)Bond.Herringbone);
            bond.AddNamedValue("Basket weave", (int)Bond.BasketWeave);
        }

        /// <summary>Names the values of a Courses input (1 level, 0 free).</summary>
        protected static void NameCourses(Param_Integer courses)
        {
            courses.AddNamedValue("Level", (int)Courses.Level);
            courses.AddNamedValue("Free", (int)Courses.Free);
        }

        /// <summary>False, with an error, when <paramref name="bond"/> is not a Bond value.</summary>
        protected bool CheckBond(int bond)
        {
            if (bond >= 0 && bond <= 4)
                return true;
            AddRuntimeMessage(GH_RuntimeMessageLevel.Error, "Bond is 0 (stack), 1 (staggered), 2 (running bond), 3 (herringbone) or 4 (basket weave), not " + bond + ".");
            return false;
        }

        /// <summary>False, with an error, when <paramref name="courses"/> is not a Courses value.</summary>
        protected bool CheckCourses(int courses)
        {
            if (courses == (int)Courses.Free || courses == (int)Courses.Level)
                return true;
            AddRuntimeMessage(GH_RuntimeMessageLevel.Error, "Courses is 1 (level) or 0 (free), not " + courses + ".");
            return false;
        }

        /// <summary>The Zones input as bonds, one per face (-1, the Bond input, is null); null
        /// with an error naming the first item that is no bond code. Empty: no zones, an
        /// empty array.</summary>
        protected Bond?[] ZoneBonds(IList<int> zones)
        {
            for (int k = 0; k < zones.Count; k++)
                if (zones[k] < -1 || zones[k] > 4)
                {
                    AddRuntimeMessage(GH_RuntimeMessageLevel.Error, "Zones item " + k + " is " + zones[k] + ": give -1 (the Bond input), 0 (stack), 1 (staggered), 2 (running bond), 3 (herringbone) or 4 (basket weave), one per face.");
                    return null;
                }
            return zones.Select(z => z < 0 ? (Bond?)null : (Bond)z).ToArray();
        }

        /// <summary>The courses to lay: free, with a remark, when level ones were asked for but
        /// the bond or a zone (codes as the Bond input) is herringbone or basket weave, which lay
        /// tiles both ways (as the command line's run chooses).</summary>
        protected int CoursesFor(int bond, IEnumerable<int> zones, int courses)
        {
            Func<int, bool> bothWays = b => b == (int)Bond.Herringbone || b == (int)Bond.BasketWeave;
            if (courses != (int)Courses.Level || !(bothWays(bond) || zones.Any(bothWays)))
                return courses;
            AddRuntimeMessage(GH_RuntimeMessageLevel.Remark, "Herringbone and basket weave lay tiles both ways: laid in free courses.");
            return (int)Courses.Free;
        }

        protected static T Unwrap<T>(IGH_DataAccess access, int index) where T : class
        {
            object value = null;
            if (!access.GetData(index, ref value) || value == null)
                return null;
            // A generic parameter hands over its items wrapped (GH_ObjectWrapper): the wrapped
            // object is the goo's script variable.
            var goo = value as Grasshopper.Kernel.Types.IGH_Goo;
            return (goo != null ? goo.ScriptVariable() : value) as T;
        }
    }

    /// <summary>A component whose solve runs on a background thread, one job per iteration,
    /// keyed by its inputs (BackgroundJobs in the wrapper). While a job runs, the outputs are
    /// empty and the component's message shows the progress; when it ends, a new solution is
    /// scheduled and the outputs are set from the result. Changed inputs cancel the old job;
    /// the context menu cancels or restarts. Worker threads never touch the Rhino or
    /// Grasshopper document: the work gets copies made on the UI thread.</summary>
    public abstract class BackgroundComponent<TResult> : ComponentBase where TResult : class
    {
        readonly BackgroundJobs<TResult> jobs;

        protected BackgroundComponent(string name, string nickname, string description, string subcategory)
            : base(name, nickname, description, subcategory)
        {
            jobs = new BackgroundJobs<TResult>(Finished, Progressed, 0.25);
        }

        protected override void BeforeSolveInstance()
        {
            NativeSetup.Ensure();
            jobs.BeginPass();
            base.BeforeSolveInstance();
        }

        protected override void AfterSolveInstance()
        {
            jobs.EndPass();
            Message = jobs.Summary;
            base.AfterSolveInstance();
        }

        /// <summary>The result for this iteration's inputs, or null while it is being solved,
        /// cancelled or failed (each with a runtime message).</summary>
        protected TResult Solve(IGH_DataAccess access, InputKey key, Func<CancellationToken, IProgress<double>, TResult> work)
        {
            JobStatus<TResult> status = jobs.Request(access.Iteration, key.ToString(), work);
            switch (status.State)
            {
                case JobState.Running:
                    AddRuntimeMessage(GH_RuntimeMessageLevel.Remark, "Solving in the background; the outputs follow when it is done (right-click: Cancel solve).");
                    return null;
                case JobState.Cancelled:
                    AddRuntimeMessage(GH_RuntimeMessageLevel.Warning, "Cancelled: change an input, or right-click: Solve again.");
                    return null;
                case JobState.Failed:
                    Show(UserMessage.For(status.Error));
                    return null;
                default:
                    return status.Result;
            }
        }

        // Worker thread: a job ended. On the UI thread, schedule a solution that re-solves this
        // component (it then reads the result).
        void Finished()
        {
            Rhino.RhinoApp.InvokeOnUiThread(new Action(() =>
            {
                GH_Document document = OnPingDocument();
                if (document != null)
                    document.ScheduleSolution(5, d => ExpireSolution(false));
            }));
        }

        // Worker thread: progress. On the UI thread, show it under the component.
        void Progressed()
        {
            Rhino.RhinoApp.InvokeOnUiThread(new Action(() =>
            {
                Message = jobs.Summary;
                OnDisplayExpired(true);
            }));
        }

        protected override void AppendAdditionalComponentMenuItems(ToolStripDropDown menu)
        {
            Menu_AppendItem(menu, "Cancel solve", (sender, e) =>
            {
                if (jobs.CancelAll() > 0)
                    ExpireSolution(true);
            }, jobs.RunningCount > 0);
            Menu_AppendItem(menu, "Solve again", (sender, e) =>
            {
                jobs.Restart();
                ExpireSolution(true);
            }, true);
            base.AppendAdditionalComponentMenuItems(menu);
        }

        public override void RemovedFromDocument(GH_Document document)
        {
            jobs.CancelAll();
            jobs.Restart();
            base.RemovedFromDocument(document);
        }

        public override void DocumentContextChanged(GH_Document document, GH_DocumentContext context)
        {
            if (context == GH_DocumentContext.Close || context == GH_DocumentContext.Unloaded)
            {
                jobs.CancelAll();
                jobs.Restart();
            }
            base.DocumentContextChanged(document, context);
        }
    }

    /// <summary>Points the wrapper at the plug-in's folder before the first native call: the
    /// .gha's path as Grasshopper's component server knows it (it knows it even when the
    /// assemblies were loaded from bytes, COFF loading, where Assembly.Location is empty), else
    /// the assembly's own location. TILEPATTERN_LIB, if set, wins.</summary>
    internal static class NativeSetup
    {
        static int done;

        public static void Ensure()
        {
            if (Interlocked.Exchange(ref done, 1) != 0)
                return;
            try
            {
                if (!string.IsNullOrEmpty(Environment.GetEnvironmentVariable("TILEPATTERN_LIB")))
                    return;
                string gha = null;
                GH_AssemblyInfo info = Grasshopper.Instances.ComponentServer.FindAssembly(TilePatternInfo.AssemblyId);
                if (info != null)
                    gha = info.Location;
                string folder = PluginLocation.Folder(gha, typeof(NativeSetup).Assembly.Location);
                if (folder != null)
                    TilePatternEngine.UseNativeLibrary(folder);
            }
            catch (Exception)
            {
                // The wrapper's own search still applies; a missing library is reported by the solve.
            }
        }
    }
}

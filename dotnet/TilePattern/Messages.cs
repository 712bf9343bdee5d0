// Every failure of a stage as one sentence for a person, with how bad it is: what a host (the
// Grasshopper components) shows as a runtime message.
using System;

namespace TilePattern
{
    /// <summary>How a host should show a message (Grasshopper: error, warning, remark).</summary>
    public enum MessageLevel
    {
        Remark,
        Warning,
        Error,
    }

    /// <summary>A message for a person.</summary>
    public sealed class UserMessage
    {
        public UserMessage(MessageLevel level, string text)
        {
            Level = level;
            Text = text;
        }

        public MessageLevel Level { get; private set; }
        public string Text { get; private set; }

        public override string ToString()
        {
            return Level + ": " + Text;
        }

        /// <summary>The message for a failure of a stage. A stale native library (a function
        /// this wrapper calls is missing: EntryPointNotFoundException) and one built for another
        /// processor or system (BadImageFormatException) are named as such, with where the
        /// library was loaded from.</summary>
        public static UserMessage For(Exception e)
        {
            if (e == null)
                throw new ArgumentNullException("e");
            var inner = e as AggregateException;
            if (inner != null && inner.InnerExceptions.Count == 1)
                return For(inner.InnerExceptions[0]);
            if (e is TilePatternCanceledException || e is OperationCanceledException)
                return new UserMessage(MessageLevel.Warning, "Cancelled.");
            if (e is InvalidMeshException)
                return new UserMessage(MessageLevel.Error, "The mesh was refused: " + ((TilePatternException)e).NativeMessage);
            if (e is InvalidPatternException)
                return new UserMessage(MessageLevel.Error, "The pattern does not fit this quad mesh (was it solved on another one?): " + ((TilePatternException)e).NativeMessage);
            if (e is InvalidArgumentException)
                return new UserMessage(MessageLevel.Error, "Invalid input: " + ((TilePatternException)e).NativeMessage);
            if (e is NativePanicException)
                return new UserMessage(MessageLevel.Error, "Internal error in the TilePattern library (please report it): " + ((TilePatternException)e).NativeMessage);
            if (e is SolverTimeLimitException)
                return new UserMessage(MessageLevel.Error, "The time limit passed before any result was ready; give it more time: " + ((TilePatternException)e).NativeMessage);
            var tp = e as TilePatternException;
            if (tp != null)
                return new UserMessage(MessageLevel.Error, tp.Status + ": " + tp.NativeMessage);
            if (e is EntryPointNotFoundException)
                return new UserMessage(MessageLevel.Error, "The TilePattern native library" + Where() + " is older or newer than this plug-in: it lacks a function the plug-in calls ("
                    + e.Message + "). Install the plug-in and its native library (runtimes/<platform>/native/) from the same release, and restart Rhino.");
            if (e is BadImageFormatException)
                return new UserMessage(MessageLevel.Error, "The TilePattern native library" + Where() + " is built for another processor or operating system than this Rhino ("
                    + Architecture() + "): install the build for this platform (runtimes/<platform>/native/), and restart Rhino. (" + e.Message + ")");
            if (e is DllNotFoundException)
                return new UserMessage(MessageLevel.Error, e.Message);
            if (e is ObjectDisposedException)
                return new UserMessage(MessageLevel.Error, "The input was released: " + e.Message);
            if (e is ArgumentException)
                return new UserMessage(MessageLevel.Error, e.Message);
            return new UserMessage(MessageLevel.Error, e.GetType().Name + ": " + e.Message);
        }

        /// <summary>What a host should say about a tiling's joints: the fit's result (a remark;
        /// a warning when its time limit cut it short), and overlaps between tiles (a warning
        /// when one is deeper than the fit leaves (by default a twentieth of the joint, at least
        /// a three-hundredth of the tile's width), or any
        /// overlap without the fit; else a remark). Lengths in model units.</summary>
        public static UserMessage[] ForJoints(Report report)
        {
            if (report == null)
                throw new ArgumentNullException("report");
            var messages = new System.Collections.Generic.List<UserMessage>();
            var culture = System.Globalization.CultureInfo.InvariantCulture;
            JointReport joints = report.Joints;
            FitReport fit = report.Fit;
            if (fit != null)
            {
                string figures = joints.BeforeFit == null ? "" : string.Format(culture, "; p95 |gap - joint| {0:G3} before, {1:G3} after",
                    joints.BeforeFit.P95Deviation, joints.P95Deviation);
                string cuts = joints.FitCuts > 0 ? string.Format(culture, "; {0} tiles cut where they could not fit", joints.FitCuts) : "";
                if (fit.Status == FitStatus.TimeLimit)
                    messages.Add(new UserMessage(MessageLevel.Warning, "The fit of the joints reached its time limit after "
                        + fit.Iterations.ToString(culture) + " steps: the best placement so far is kept" + figures + cuts + "."));
                else
                    messages.Add(new UserMessage(MessageLevel.Remark, "Joints fitted (" + fit.StatusText + ", " + fit.Iterations.ToString(culture)
                        + " steps)" + figures + cuts + "."));
            }
            if (joints.Overlaps > 0)
            {
                // A report without the figure (an older library) leaves no overlap uncut.
                double tolerance = fit != null && !double.IsNaN(fit.OverlapTolerance) ? fit.OverlapTolerance : 0.0;
                if (joints.MaxOverlap > tolerance * (1 + 1e-9))
                    messages.Add(new UserMessage(MessageLevel.Warning, string.Format(culture,
                        "{0} pairs of tiles overlap, the deepest by {1:G3}{2}.", joints.Overlaps, joints.MaxOverlap,
                        fit == null ? " (turn the fit on, or is the tile too large for the quads?)" : "")));
                else
                    messages.Add(new UserMessage(MessageLevel.Remark, string.Format(culture,
                        "{0} pairs of tiles overlap by at most {1:G3}, within the fit's tolerance.", joints.Overlaps, joints.MaxOverlap)));
            }
            return messages.ToArray();
        }

        /// <summary>What a host should say about the laying order (a remark; null when the report
        /// has none): tiles on the supports, tiles that need a prop, and how many of the whole
        /// tiles on slopes over 20 degrees run up the slope instead of along the level (level
        /// courses are level only where one family of quad rows is).</summary>
        public static UserMessage ForLaying(Report report)
        {
            if (report == null)
                throw new ArgumentNullException("report");
            SequenceReport s = report.Sequence;
            if (s == null)
                return null;
            var culture = System.Globalization.CultureInfo.InvariantCulture;
            string text = string.Format(culture, "Laying order: {0} tiles on the supports, {1} need a prop", s.SupportTiles, s.Unsupported);
            if (s.SlopedTiles > 0)
                text += string.Format(culture, "; {0} of the {1} whole tiles on slopes over 20 degrees run up them", s.ClimbingTiles, s.SlopedTiles);
            return new UserMessage(MessageLevel.Remark, text + ".");
        }

        /// <summary>What a host should say about the tries of <see cref="TilePatternEngine.Run"/>
        /// (a remark): which try's tiles were kept, with its p95 |gap - joint| (model units),
        /// share of tiles cut, coverage and score (lower is better; tries whose joints are not
        /// flagged wide come first), then every other try's, and any try that reached a time
        /// limit (and whether that ended the tries) or failed. With no tries listed (one quad mesh tried): a
        /// remark saying so.</summary>
        public static UserMessage ForTries(Report report)
        {
            if (report == null)
                throw new ArgumentNullException("report");
            var culture = System.Globalization.CultureInfo.InvariantCulture;
            TryReport[] tries = report.Tries ?? new TryReport[0];
            int chosen = report.ChosenTry;
            if (tries.Length == 0 || chosen < 0 || chosen >= tries.Length)
                return new UserMessage(MessageLevel.Remark, "One quad mesh tried (Tries 1, or 0 on a surface of more than 10,000 quads).");
            Func<int, string> head = k => string.Format(culture, "try {0} ({1}{2}{3}renormalisation {4:G3})", k + 1,
                tries[k].Field == null || tries[k].Field == "curvature" ? "" : tries[k].Field + " field, ",
                tries[k].QuadsAlongCourses ? "quads along the courses, " : "",
                tries[k].BoundaryFree ? "boundary free, " : "", tries[k].Renormalisation);
            Func<int, string> figures = k =>
            {
                TryReport t = tries[k];
                if (t.Failed != null)
                    return "failed: " + t.Failed;
                string text = string.Format(culture, "p95 |gap - joint| {0:G3}{1}, {2:0.#} % of tiles cut{3}, coverage {4:0.###}, score {5:0.##}", t.P95Deviation,
                    t.WideJoints ? " (wide joints)" : "", 100 * t.CutShare, t.FitCuts ? " (over 1 %)" : "", t.Coverage, t.Score);
                if (t.LimitReached != null)
                    text += ", its " + t.LimitReached + " stage reached its time limit, so "
                        + (t.EndedTries ? "no further try was made" : "its tiles depend on the machine's speed")
                        + (k == chosen ? "" : " and it is not kept");
                return text;
            };
            var others = new System.Collections.Generic.List<string>();
            for (int k = 0; k < tries.Length; k++)
                if (k != chosen)
                    others.Add(head(k) + ": " + figures(k));
            string rest = others.Count == 0 ? "" : " " + char.ToUpperInvariant(others[0][0]) + string.Join("; ", others.ToArray()).Substring(1) + ".";
            return new UserMessage(MessageLevel.Remark, string.Format(culture, "{0} {1}: the tiles of {2} are kept: {3}.{4}",
                tries.Length, tries.Length == 1 ? "try" : "tries", head(chosen), figures(chosen), rest));
        }

        static string Where()
        {
            try
            {
                string path = NativeLibraryLoader.LoadedPath;
                return string.IsNullOrEmpty(path) ? "" : " (" + path + ")";
            }
            catch (Exception)
            {
                return "";
            }
        }

        static string Architecture()
        {
            try
            {
                return System.Runtime.InteropServices.RuntimeInformation.OSDescription.Trim() + ", "
                    + System.Runtime.InteropServices.RuntimeInformation.ProcessArchitecture;
            }
            catch (Exception)
            {
                return IntPtr.Size == 8 ? "64-bit" : "32-bit";
            }
        }
    }
}

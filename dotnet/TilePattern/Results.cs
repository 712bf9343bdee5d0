// What the stages return: a Pattern (keeps its native handle for the tile stage), Tiles and
// the Report (plain data, copied out of the library); and what a whole run keeps (RunResult).
using System;
using System.Collections.Generic;
using System.Linq;
using System.Threading;

namespace TilePattern
{
    /// <summary>A solved matching. Its numbers and pairs are plain data, readable at any time;
    /// it also owns the native pattern and the native quad mesh it was solved on, which
    /// <c>TilePatternEngine.Tiles</c> needs. Dispose releases
    /// them (a forgotten Dispose is caught by the SafeHandles' finalizers).</summary>
    public sealed class Pattern : IDisposable
    {
        readonly PatternHandle handle;
        readonly MeshHandle mesh;
        int disposed;

        internal Pattern(PolyMesh quads, MeshHandle mesh, PatternHandle handle)
        {
            this.handle = handle;
            this.mesh = mesh;
            QuadMesh = quads;
            TpPatternSummary s;
            Native.Check(NativeMethods.tp_pattern_summary(handle, out s));
            FaceCount = Native.Count(s.faces);
            ExcludedCount = Native.Count(s.excluded);
            NonQuadCount = Native.Count(s.non_quad);
            ContinuousJoints = Native.Count(s.continuous_joints);
            ShiftedPairs = Native.Count(s.shifted_pairs);
            Objective = s.objective;
            Bound = s.bound;
            Gap = s.gap;
            Seconds = s.seconds;
            Status = (SolveStatus)s.status;
            int source;
            Native.Check(NativeMethods.tp_pattern_bound_source(handle, out source));
            BoundSource = (BoundSource)source;

            var flat = new uint[checked(2 * Native.Count(s.pairs))];
            Native.Check(NativeMethods.tp_pattern_copy_pairs(handle, flat, Native.Size(flat.Length)));
            Pairs = new FacePair[flat.Length / 2];
            for (int k = 0; k < Pairs.Length; k++)
                Pairs[k] = new FacePair(checked((int)flat[2 * k]), checked((int)flat[2 * k + 1]));
            var unpaired = new uint[Native.Count(s.unpaired)];
            Native.Check(NativeMethods.tp_pattern_copy_unpaired(handle, unpaired, Native.Size(unpaired.Length)));
            Unpaired = PolyMesh.ToInt(unpaired);

            // The native pattern and mesh live as long as this object: tell the GC about them
            // (an estimate: the mesh's coordinates and indices as the library stores them, and
            // the pattern's per-face arrays), so that undisposed patterns are collected in time.
            long meshBytes = 24L * quads.VertexCount + 8L * quads.FaceIndexLength + 16L * FaceCount + 256;
            mesh.AddPressure(meshBytes);
            handle.AddPressure(24L * FaceCount + 16L * Pairs.Length + 256);
        }

        /// <summary>Bytes of native memory announced to the GC for this pattern and its mesh
        /// (0 once disposed).</summary>
        internal long NativeBytesEstimate
        {
            get { return IsDisposed ? 0 : 24L * QuadMesh.VertexCount + 8L * QuadMesh.FaceIndexLength + 16L * FaceCount + 256 + 24L * FaceCount + 16L * Pairs.Length + 256; }
        }

        /// <summary>Which argument proved <see cref="Bound"/> (with an optimal status: which closed the gap).</summary>
        public BoundSource BoundSource { get; private set; }

        /// <summary>The quad mesh the pattern was solved on.</summary>
        public PolyMesh QuadMesh { get; private set; }

        /// <summary>Faces of the mesh.</summary>
        public int FaceCount { get; private set; }

        /// <summary>Matched pairs (full tiles), a &lt; b, sorted.</summary>
        public FacePair[] Pairs { get; private set; }

        /// <summary>Unpaired quads (half tiles, each needs a cut).</summary>
        public int[] Unpaired { get; private set; }

        public int ExcludedCount { get; private set; }

        /// <summary>Faces that are not quads (no tile).</summary>
        public int NonQuadCount { get; private set; }

        public int ContinuousJoints { get; private set; }

        public int ShiftedPairs { get; private set; }

        public double Objective { get; private set; }

        /// <summary>Proven upper bound on the objective.</summary>
        public double Bound { get; private set; }

        /// <summary>(bound - objective) / max(bound, 1).</summary>
        public double Gap { get; private set; }

        /// <summary>Wall-clock seconds of the solve.</summary>
        public double Seconds { get; private set; }

        public SolveStatus Status { get; private set; }

        public bool IsDisposed { get { return disposed != 0; } }

        internal PatternHandle Handle
        {
            get
            {
                if (IsDisposed)
                    throw new ObjectDisposedException("Pattern");
                return handle;
            }
        }

        internal MeshHandle MeshHandle
        {
            get
            {
                if (IsDisposed)
                    throw new ObjectDisposedException("Pattern");
                return mesh;
            }
        }

        /// <summary>Releases the native pattern and mesh; safe to call more than once.</summary>
        public void Dispose()
        {
            if (Interlocked.Exchange(ref disposed, 1) != 0)
                return;
            handle.Dispose();
            mesh.Dispose();
        }

        public override string ToString()
        {
            return string.Format(System.Globalization.CultureInfo.InvariantCulture,
                "{0} pairs, {1} unpaired, {2} continuous joints, objective {3}, bound {4}, {5}",
                Pairs.Length, Unpaired.Length, ContinuousJoints, Objective, Bound, Status);
        }
    }

    /// <summary>What <see cref="TilePatternEngine.Run"/> keeps: the quad mesh, the pattern and
    /// the tiles of the try that fit best (the tiling's <see cref="Report.Tries"/> lists every
    /// try, <see cref="Report.ChosenTry"/> the one kept). <see cref="Pattern"/> owns native memory
    /// (the pattern and the quad mesh, for another <c>TilePatternEngine.Tiles</c>); Dispose
    /// releases it (a forgotten Dispose is caught by the SafeHandles' finalizers). The quads and
    /// the tiling are plain data, readable at any time.</summary>
    public sealed class RunResult : IDisposable
    {
        internal RunResult(Pattern pattern, Tiling tiling)
        {
            Pattern = pattern;
            Tiling = tiling;
        }

        /// <summary>The kept try's quad mesh (<see cref="TilePattern.Pattern.QuadMesh"/>).</summary>
        public PolyMesh Quads { get { return Pattern.QuadMesh; } }

        /// <summary>The kept try's pattern, solved on <see cref="Quads"/>; owns native memory.</summary>
        public Pattern Pattern { get; private set; }

        /// <summary>The kept tiles, cut to the surface's boundary, and their report.</summary>
        public Tiling Tiling { get; private set; }

        /// <summary>Releases the pattern's native memory; safe to call more than once.</summary>
        public void Dispose()
        {
            Pattern.Dispose();
        }
    }

    /// <summary>One tile: a box in its own frame, spanning [-L/2, L/2] x [-W/2, W/2] x [0, T].</summary>
    public sealed class Tile
    {
        internal Tile() { }

        /// <summary>Position in the tile list: full tiles in pair order, then half tiles in face order.</summary>
        public int Index { get; internal set; }

        public TileKind Kind { get; internal set; }

        /// <summary>8 corners as xyz (24 values): the bottom face counter-clockwise from
        /// (-x, -y), then the top face in the same order.</summary>
        public double[] Corners { get; internal set; }

        /// <summary>Frame origin (midpoint between the face centroids), xyz.</summary>
        public double[] Origin { get; internal set; }

        /// <summary>Length axis (unit), xyz.</summary>
        public double[] XAxis { get; internal set; }

        /// <summary>Width axis (unit), xyz.</summary>
        public double[] YAxis { get; internal set; }

        /// <summary>Thickness axis (unit, the surface normal side), xyz.</summary>
        public double[] ZAxis { get; internal set; }

        public double Length { get; internal set; }

        public double Width { get; internal set; }

        public double Thickness { get; internal set; }

        /// <summary>The quad faces it covers: two for a full tile, one for a half tile (a
        /// boundary tile is cut from either; a piece the library adds beyond the quad mesh may
        /// cover none). TP_NO_FACE slots are left out.</summary>
        public int[] Faces { get; internal set; }

        /// <summary>Step in the laying order, from 0.</summary>
        public int Step { get; internal set; }

        /// <summary>Kept area over face area: 1 for an uncut tile.</summary>
        public double KeptFraction { get; internal set; }

        /// <summary>Cut-list label: F (full), H (half), B1, B2, ... (boundary shapes), C1, C2,
        /// ... (shapes cut by the fit stage).</summary>
        public string Label { get; internal set; }

        /// <summary>This tile's worst joint: the largest |gap - joint| over the joints it takes
        /// part in (0 for a tile with none), in model units (tp_tiles_copy_joint_deviations).
        /// For a colour preview of the joints.</summary>
        public double JointDeviation { get; internal set; }

        /// <summary>For a cut tile (boundary or fit cut), the part of its face to keep: loops of
        /// (x, y) points in the tile's frame (x0, y0, x1, y1, ...), outer loops
        /// counter-clockwise, holes clockwise seen from +z. Empty for an uncut tile.</summary>
        public double[][] Outline { get; internal set; }

        /// <summary>Loop <paramref name="loop"/> of <see cref="Outline"/> in model
        /// coordinates, on the tile's bottom face (xyz triples).</summary>
        public double[] OutlineInModel(int loop)
        {
            double[] xy = Outline[loop];
            var xyz = new double[xy.Length / 2 * 3];
            for (int p = 0; p < xy.Length / 2; p++)
                for (int d = 0; d < 3; d++)
                    xyz[3 * p + d] = Origin[d] + xy[2 * p] * XAxis[d] + xy[2 * p + 1] * YAxis[d];
            return xyz;
        }

        /// <summary>Corner i (0-7) as {x, y, z}.</summary>
        public double[] Corner(int i)
        {
            return new[] { Corners[3 * i], Corners[3 * i + 1], Corners[3 * i + 2] };
        }
    }

    /// <summary>Tiles that share one cut shape (a row of the cut list).</summary>
    public sealed class CutGroup
    {
        /// <summary>F, H, B1, B2, ...</summary>
        public string Label { get; internal set; }
        /// <summary>"full", "half", "boundary" or "fit_cut".</summary>
        public string Kind { get; internal set; }
        public int Count { get; internal set; }
        /// <summary>Length of the blank the shape is cut from.</summary>
        public double BlankLength { get; internal set; }
        public double BlankWidth { get; internal set; }
        /// <summary>Kept area of one tile.</summary>
        public double Area { get; internal set; }
    }

    /// <summary>The tile stage's result: every tile, the report and the cut list.</summary>
    public sealed class Tiling
    {
        internal Tiling(Tile[] tiles, Report report, string cutListJson)
        {
            Tiles = tiles;
            Report = report;
            CutListJson = cutListJson;
            var groups = new List<CutGroup>();
            var list = JsonReader.Parse(cutListJson) as List<object>;
            if (list != null)
                foreach (object item in list)
                {
                    var g = item as Dictionary<string, object>;
                    var blank = g != null && g.ContainsKey("blank") ? g["blank"] as List<object> : null;
                    groups.Add(new CutGroup
                    {
                        Label = JsonAccess.Text(g, "label"),
                        Kind = JsonAccess.Text(g, "kind"),
                        Count = JsonAccess.Integer(g, "count"),
                        BlankLength = blank != null && blank.Count == 2 && blank[0] is double ? (double)blank[0] : double.NaN,
                        BlankWidth = blank != null && blank.Count == 2 && blank[1] is double ? (double)blank[1] : double.NaN,
                        Area = JsonAccess.Number(g, "area"),
                    });
                }
            CutList = groups.ToArray();
        }

        /// <summary>The cut list: one group per cut shape (tp_tiles_cutlist_json, parsed).</summary>
        public CutGroup[] CutList { get; private set; }

        /// <summary>The cut list as the library wrote it (the CLI's cutlist.json).</summary>
        public string CutListJson { get; private set; }

        public int BoundaryCount { get { return Array.FindAll(Tiles, t => t.Kind == TileKind.Boundary).Length; } }

        /// <summary>Tiles of kind <see cref="TileKind.FitCut"/> (see also
        /// <see cref="JointReport.FitCuts"/>, which counts boundary tiles the fit cut too).</summary>
        public int FitCutCount { get { return Array.FindAll(Tiles, t => t.Kind == TileKind.FitCut).Length; } }

        /// <summary>Full tiles in pair order, then half tiles in face order, then filler pieces
        /// on no quad (<see cref="CuttingReport.FillerTiles"/>; not counted in
        /// <see cref="Report.FullTiles"/> or <see cref="Report.HalfTiles"/>).</summary>
        public Tile[] Tiles { get; private set; }

        public Report Report { get; private set; }

        public int FullCount { get { return Array.FindAll(Tiles, t => t.Kind == TileKind.Full).Length; } }

        public int HalfCount { get { return Array.FindAll(Tiles, t => t.Kind == TileKind.Half).Length; } }
    }

    /// <summary>Tile size and joint as used, in model units.</summary>
    public sealed class TileDimensions
    {
        public double Length { get; internal set; }
        public double Width { get; internal set; }
        public double Thickness { get; internal set; }
        public double Joint { get; internal set; }
    }

    /// <summary>The joints between neighbouring tiles: for every pair of tiles whose faces share
    /// a mesh edge, and every other pair whose outlines overlap, the signed separation of their
    /// outlines in their mean plane (the joint's width; negative: an overlap).</summary>
    public sealed class JointReport
    {
        /// <summary>Pairs of neighbouring tiles measured.</summary>
        public int Contacts { get; internal set; }
        /// <summary>Nominal joint.</summary>
        public double Joint { get; internal set; }
        /// <summary>Narrowest joint (negative: an overlap).</summary>
        public double MinGap { get; internal set; }
        /// <summary>Widest joint.</summary>
        public double MaxGap { get; internal set; }
        /// <summary>Mean joint.</summary>
        public double MeanGap { get; internal set; }
        /// <summary>95th percentile of |gap - joint|.</summary>
        public double P95Deviation { get; internal set; }
        /// <summary>Pairs of tiles that overlap.</summary>
        public int Overlaps { get; internal set; }
        /// <summary>95th percentile of the gap.</summary>
        public double P95Gap { get; internal set; }
        /// <summary>Deepest overlap (0 if none).</summary>
        public double MaxOverlap { get; internal set; }
        /// <summary>Share of joints with |gap - joint| at most 2 mm (millimetres by
        /// <see cref="TileOptions.UnitsPerMm"/>).</summary>
        public double Within2Mm { get; internal set; }
        /// <summary>Share of joints with |gap - joint| at most 5 mm.</summary>
        public double Within5Mm { get; internal set; }
        /// <summary>Tiles the fit stage cut because they could not be made to fit: those of kind
        /// <see cref="TileKind.FitCut"/> (filler pieces and tiles cut to the boundary that the fit
        /// trims too are cut anyway and not counted).</summary>
        public int FitCuts { get; internal set; }
        /// <summary>The same figures for the paper's placement, before the fit moved the tiles;
        /// null when the fit did not run (and on the figures before the fit themselves).</summary>
        public JointReport BeforeFit { get; internal set; }

        internal static JointReport Parse(Dictionary<string, object> joints)
        {
            if (joints == null)
                return null;
            return new JointReport
            {
                Contacts = JsonAccess.Integer(joints, "contacts"),
                Joint = JsonAccess.Number(joints, "joint"),
                MinGap = JsonAccess.Number(joints, "min_gap"),
                MaxGap = JsonAccess.Number(joints, "max_gap"),
                MeanGap = JsonAccess.Number(joints, "mean_gap"),
                P95Deviation = JsonAccess.Number(joints, "p95_deviation"),
                Overlaps = JsonAccess.Integer(joints, "overlaps"),
                P95Gap = JsonAccess.Number(joints, "p95_gap"),
                MaxOverlap = JsonAccess.Number(joints, "max_overlap"),
                Within2Mm = JsonAccess.Number(joints, "within_2mm"),
                Within5Mm = JsonAccess.Number(joints, "within_5mm"),
                FitCuts = JsonAccess.Integer(joints, "fit_cuts"),
                BeforeFit = Parse(JsonAccess.Object(joints, "before_fit")),
            };
        }
    }

    /// <summary>How the fit stage ended (the report's fit.status).</summary>
    public enum FitStatus
    {
        /// <summary>Further steps no longer improved the joints.</summary>
        Converged = 0,
        /// <summary>The step limit was reached first.</summary>
        IterationLimit = 1,
        /// <summary>The time limit was reached first: the best placement so far is kept.</summary>
        TimeLimit = 2,
        /// <summary>The caller cancelled (the wrapper then throws instead of returning tiles).</summary>
        Cancelled = 3,
        /// <summary>A status this wrapper does not know (see <see cref="FitReport.StatusText"/>).</summary>
        Unknown = -1,
    }

    /// <summary>What the fit stage did (the report's fit object).</summary>
    /// <summary>The pattern a tiling was built from, without its pairs (report.json's
    /// <c>pattern</c>): every field of the pattern stage's result, so that none is lost on the way.</summary>
    public sealed class PatternReport
    {
        /// <summary>Faces of the quad mesh.</summary>
        public int Faces { get; internal set; }
        /// <summary>Matched pairs: full tiles.</summary>
        public int Pairs { get; internal set; }
        /// <summary>Quads in no pair: half tiles.</summary>
        public int Unpaired { get; internal set; }
        /// <summary>Faces excluded by the caller.</summary>
        public int Excluded { get; internal set; }
        /// <summary>Faces that are not quads.</summary>
        public int NonQuad { get; internal set; }
        /// <summary>Continuous joints (eq. 2's y).</summary>
        public int ContinuousJoints { get; internal set; }
        /// <summary>Shifted pairs (eq. 3's z).</summary>
        public int ShiftedPairs { get; internal set; }
        /// <summary>Pairs of the bond's own relation (herringbone, basket weave).</summary>
        public int BondPairs { get; internal set; }
        /// <summary>Objective of the matching.</summary>
        public double Objective { get; internal set; }
        /// <summary>Proven bound on the objective.</summary>
        public double Bound { get; internal set; }
        /// <summary>Relative gap.</summary>
        public double Gap { get; internal set; }
        /// <summary>"optimal", "time_limit" or "feasible".</summary>
        public string StatusText { get; internal set; }
        /// <summary>Which argument proved <see cref="Bound"/>.</summary>
        public BoundSource BoundSource { get; internal set; }
        /// <summary>"matching", "patches", "whole_program" or "linear_relaxation".</summary>
        public string BoundSourceText { get; internal set; }
        /// <summary>Seconds of the pattern stage.</summary>
        public double Seconds { get; internal set; }

        internal static PatternReport Parse(Dictionary<string, object> p)
        {
            if (p == null)
                return null;
            var r = new PatternReport
            {
                Faces = JsonAccess.Integer(p, "faces"),
                Pairs = JsonAccess.Integer(p, "pairs"),
                Unpaired = JsonAccess.Integer(p, "unpaired"),
                Excluded = JsonAccess.Integer(p, "excluded"),
                NonQuad = JsonAccess.Integer(p, "non_quad"),
                ContinuousJoints = JsonAccess.Integer(p, "continuous_joints"),
                ShiftedPairs = JsonAccess.Integer(p, "shifted_pairs"),
                BondPairs = JsonAccess.Integer(p, "bond_pairs"),
                Objective = JsonAccess.Number(p, "objective"),
                Bound = JsonAccess.Number(p, "bound"),
                Gap = JsonAccess.Number(p, "gap"),
                StatusText = JsonAccess.Text(p, "status") ?? "",
                BoundSourceText = JsonAccess.Text(p, "bound_source") ?? "",
                Seconds = JsonAccess.Number(p, "seconds"),
            };
            switch (r.BoundSourceText)
            {
                case "patches": r.BoundSource = BoundSource.Patches; break;
                case "whole_program": r.BoundSource = BoundSource.WholeProgram; break;
                case "linear_relaxation": r.BoundSource = BoundSource.LinearRelaxation; break;
                default: r.BoundSource = BoundSource.Matching; break;
            }
            return r;
        }
    }

    public sealed class FitReport
    {
        /// <summary>Parsed from <see cref="StatusText"/>.</summary>
        public FitStatus Status { get; internal set; }
        /// <summary>"converged", "iteration_limit", "time_limit" or "cancelled".</summary>
        public string StatusText { get; internal set; }
        /// <summary>Levenberg-Marquardt steps taken.</summary>
        public int Iterations { get; internal set; }
        /// <summary>Sum of squared joint, bond and anchor residuals before the fit (model units squared).</summary>
        public double ObjectiveBefore { get; internal set; }
        /// <summary>The same after the fit.</summary>
        public double ObjectiveAfter { get; internal set; }
        /// <summary>Mean distance a tile's origin moved from the paper's placement.</summary>
        public double MeanMove { get; internal set; }
        /// <summary>Largest such distance.</summary>
        public double MaxMove { get; internal set; }
        /// <summary>Overlaps up to this depth were left, deeper ones cut (model units).</summary>
        public double OverlapTolerance { get; internal set; }
        /// <summary>Standard pieces (halves or whole tiles) the fit laid whole in rooms it left
        /// between the heads of a course, with their joints closed around them: no cut on site
        /// (0 in reports of libraries before them).</summary>
        public int RoomPieces { get; internal set; }

        internal static FitReport Parse(Dictionary<string, object> fit)
        {
            if (fit == null)
                return null;
            var r = new FitReport
            {
                StatusText = JsonAccess.Text(fit, "status") ?? "",
                Iterations = JsonAccess.Integer(fit, "iterations"),
                ObjectiveBefore = JsonAccess.Number(fit, "objective_before"),
                ObjectiveAfter = JsonAccess.Number(fit, "objective_after"),
                MeanMove = JsonAccess.Number(fit, "mean_move"),
                MaxMove = JsonAccess.Number(fit, "max_move"),
                OverlapTolerance = JsonAccess.Number(fit, "overlap_tolerance"),
                RoomPieces = Math.Max(0, JsonAccess.Integer(fit, "room_pieces")),
            };
            switch (r.StatusText)
            {
                case "converged": r.Status = FitStatus.Converged; break;
                case "iteration_limit": r.Status = FitStatus.IterationLimit; break;
                case "time_limit": r.Status = FitStatus.TimeLimit; break;
                case "cancelled": r.Status = FitStatus.Cancelled; break;
                default: r.Status = FitStatus.Unknown; break;
            }
            return r;
        }
    }

    /// <summary>Tiles cut to the surface's boundary, and how much of the surface the tiles cover.</summary>
    public sealed class CuttingReport
    {
        public int BoundaryTiles { get; internal set; }
        /// <summary>Filler pieces on no quad, where the quad mesh (or a course the fit left
        /// short) ends before the surface's edge, and in the holes the fit left.</summary>
        public int FillerTiles { get; internal set; }
        /// <summary>Of <see cref="FillerTiles"/>, the pieces filling holes the fit left (where
        /// courses converge or part, and along the edge where the edge's filler pieces did not
        /// reach).</summary>
        public int TearPieces { get; internal set; }
        /// <summary>Of <see cref="TearPieces"/>, those cut to the room their neighbours leave
        /// away from the surface's edge: the cuts the fit's holes ask for (the fit_cuts
        /// warning counts them with the tiles cut to fit).</summary>
        public int TearCuts { get; internal set; }
        /// <summary>Of <see cref="TearPieces"/>, whole half tiles laid where a hole's room held
        /// one with its joints within half a joint of the nominal one (no cut on site; they
        /// are in the cut list's H).</summary>
        public int TearHalves { get; internal set; }
        /// <summary>Tiles entirely off the surface (dropped).</summary>
        public int OutsideTiles { get; internal set; }
        /// <summary>Pieces too narrow to keep (dropped): cut to the boundary, or by the fit.</summary>
        public int Slivers { get; internal set; }
        /// <summary>Distinct boundary cut shapes (B labels).</summary>
        public int BoundaryShapes { get; internal set; }
        public double SurfaceArea { get; internal set; }
        public double TileArea { get; internal set; }
        /// <summary>Share of the surface under a kept tile face or its half joint.</summary>
        public double Coverage { get; internal set; }
    }

    /// <summary>Why a tiling deserves a second look (enum TpWarning of the C header; the
    /// numbers are stable).</summary>
    public enum TilingWarningCode
    {
        /// <summary>The surface has no boundary (a sphere, a torus, a box).</summary>
        ClosedSurface = 1,
        /// <summary>The surface falls into several pieces that share no edge.</summary>
        SeveralPieces = 2,
        /// <summary>Most face normals point down: tiles are laid on the underside.</summary>
        NormalsDown = 3,
        /// <summary>The tile does not fit the half-tile model (length about 2 x width + joint).</summary>
        TileShape = 4,
        /// <summary>The surface turns a lot over one tile length.</summary>
        TileVsCurvature = 5,
        /// <summary>The tiles cover less than 0.95 of the surface.</summary>
        LowCoverage = 6,
        /// <summary>Tiles were left out (off the surface, or slivers).</summary>
        TilesDropped = 7,
        /// <summary>Nothing to lay from: a closed surface, or a level one on the ground.</summary>
        NoSupport = 8,
        /// <summary>Reading a file joined coincident vertices.</summary>
        VerticesWelded = 9,
        /// <summary>The fit stage cut more than 1 % of the tiles (courses converge or diverge).</summary>
        FitCuts = 10,
        /// <summary>The joints' p95 deviation from the nominal joint is more than half the joint.</summary>
        WideJoints = 11,
        /// <summary>The surface folds back on itself (neighbouring faces turned by more than 120 degrees).</summary>
        FoldedSurface = 12,
        /// <summary>Reading a file turned faces over to agree with their neighbours.</summary>
        NormalsUnified = 13,
        /// <summary>Fewer than 70 % of the quad edges are within 20 % of half a tile.</summary>
        QuadSize = 14,
        /// <summary>Tiles stand off the surface by more than their thickness (creases across the input's triangles, facets coarser than a tile).</summary>
        TilesOffSurface = 15,
        /// <summary>The surface has openings smaller than a tile (often a face missing from the mesh); the tiles over them are cut around them.</summary>
        SmallOpenings = 16,
        /// <summary>The surface faces along another axis than up (a model whose up is Y, tiled with up Z): set the up direction.</summary>
        UpAxis = 17,
        /// <summary>The quad mesh does not lie on the surface the tiles are cut to (quads made from another surface, or the surface moved, scaled or in other units since).</summary>
        QuadsOffSurface = 18,
        /// <summary>Faces of more than four corners, larger than a tile and not flat: the surface inside them is a guess; give the surface as triangles or quads.</summary>
        CurvedPolygons = 19,
    }

    /// <summary>One warning: odd input or a result to look at twice, with what to do.</summary>
    public sealed class TilingWarning
    {
        /// <summary>The code (report.json's name for it in <see cref="Name"/>).</summary>
        public TilingWarningCode Code { get; internal set; }
        /// <summary>The code as report.json writes it, e.g. "closed_surface".</summary>
        public string Name { get; internal set; }
        /// <summary>What was found and what to do.</summary>
        public string Message { get; internal set; }
        /// <summary>The face of the surface the message names (report.json's <c>face</c>:
        /// folded_surface, curved_polygons), counted from 0; -1 when it names none.</summary>
        public int Face { get; internal set; }

        public override string ToString()
        {
            return "[" + Name + "] " + Message;
        }
    }

    /// <summary>The laying order's summary.</summary>
    public sealed class SequenceReport
    {
        /// <summary>What the vault stands on: "edges" (the lowest boundary), "no_boundary" (a
        /// closed surface: no tile stands on a support) or "level" (a level surface on the
        /// ground: no tile needs a prop).</summary>
        public string Support { get; internal set; }
        /// <summary>Tiles standing on the supports.</summary>
        public int SupportTiles { get; internal set; }
        /// <summary>Tiles that at their step touch no lower laid tile and stand on no support.</summary>
        public int Unsupported { get; internal set; }
        /// <summary>Whole tiles (uncut, longer than wide) on slopes steeper than 20 degrees.</summary>
        public int SlopedTiles { get; internal set; }
        /// <summary>Of <see cref="SlopedTiles"/>, those whose length runs up the slope (within 45
        /// degrees of it) rather than along the level: level courses keep it near zero only where
        /// one family of quad rows is level (barrels, webs), not on shells curved both ways.</summary>
        public int ClimbingTiles { get; internal set; }
    }

    /// <summary>One try of <see cref="TilePatternEngine.Run"/> (report.json's <c>tries</c>):
    /// the tiles laid on one quad mesh of the surface, and how well they fit.</summary>
    public sealed class TryReport
    {
        /// <summary>The field's renormalisation strength of this try's quad mesh.</summary>
        public double Renormalisation { get; internal set; }
        /// <summary>What its field follows besides a designer's field and guide curves:
        /// "curvature" (the default; also for reports written before tries named it), "smooth"
        /// (nothing: the boundary and smoothness alone, the last automatic try), "direction" or
        /// "angle".</summary>
        public string Field { get; internal set; }
        /// <summary>Whether its quads are laid out for level courses, half a tile and a joint
        /// along them and a course's pitch across (the fifth automatic try; report.json's
        /// <c>quads_along_courses</c>).</summary>
        public bool QuadsAlongCourses { get; internal set; }
        /// <summary>Whether its quads follow no boundary loop, not even one with corners, their
        /// rows cut to curved edges instead (the sixth automatic try; report.json's
        /// <c>boundary_free</c>).</summary>
        public bool BoundaryFree { get; internal set; }
        /// <summary>Faces of its quad mesh (0 when it failed).</summary>
        public int Quads { get; internal set; }
        /// <summary>Interior irregular vertices of its quad mesh.</summary>
        public int InteriorIrregularVertices { get; internal set; }
        /// <summary>Its joints' p95 |gap - joint| after the fit (model units).</summary>
        public double P95Deviation { get; internal set; }
        /// <summary>Tiles cut to fit and pieces cut inside the fit's holes, per full and half tile (0 to 1).</summary>
        public double CutShare { get; internal set; }
        /// <summary>Share of the surface its tiles cover.</summary>
        public double Coverage { get; internal set; }
        /// <summary>Whether its report warned that the joints stray (wide_joints); tries without
        /// the warning are kept before tries with it.</summary>
        public bool WideJoints { get; internal set; }
        /// <summary>Whether its report warned that the fit cut more than 1 % of the tiles
        /// (fit_cuts); among tries whose joints are not flagged, tries without this warning are
        /// kept first.</summary>
        public bool FitCuts { get; internal set; }
        /// <summary>percent of tiles cut + p95 per half joint + percent uncovered + a quarter of the
        /// percent of pieces cut at the edge: lower is better; NaN when the try failed.</summary>
        public double Score { get; internal set; }
        /// <summary>Seconds of this try, all stages.</summary>
        public double Seconds { get; internal set; }
        /// <summary>"pattern" or "fit" when that stage reached its time limit in this try (its
        /// tiles then depend on the machine's speed, and a later try that reaches one is not
        /// kept); null otherwise.</summary>
        public string LimitReached { get; internal set; }
        /// <summary>Whether reaching that limit ended the tries (no further try was made): every
        /// limit does except the first try's pattern stage's when a later try's pattern stage
        /// has a shorter limit (the report's <c>ended_tries</c>).</summary>
        public bool EndedTries { get; internal set; }
        /// <summary>Why the try gave no tiles, or null.</summary>
        public string Failed { get; internal set; }

        internal static TryReport Parse(Dictionary<string, object> t)
        {
            return new TryReport
            {
                Renormalisation = JsonAccess.Number(t, "renormalisation"),
                Field = JsonAccess.Text(t, "field") ?? "curvature",
                QuadsAlongCourses = JsonAccess.Flag(t, "quads_along_courses"),
                BoundaryFree = JsonAccess.Flag(t, "boundary_free"),
                Quads = JsonAccess.Integer(t, "quads"),
                InteriorIrregularVertices = JsonAccess.Integer(t, "interior_irregular_vertices"),
                P95Deviation = JsonAccess.Number(t, "p95_deviation"),
                CutShare = JsonAccess.Number(t, "cut_share"),
                Coverage = JsonAccess.Number(t, "coverage"),
                WideJoints = JsonAccess.Flag(t, "wide_joints"),
                FitCuts = JsonAccess.Flag(t, "fit_cuts"),
                Score = JsonAccess.Number(t, "score"),
                Seconds = JsonAccess.Number(t, "seconds"),
                LimitReached = JsonAccess.Text(t, "limit_reached"),
                EndedTries = JsonAccess.Flag(t, "ended_tries"),
                Failed = JsonAccess.Text(t, "failed"),
            };
        }
    }

    /// <summary>The report of tp_tiles_report_json (the CLI's report.json without units).</summary>
    public sealed class Report
    {
        internal Report() { }

        public int Faces { get; private set; }
        public int FullTiles { get; private set; }
        public int HalfTiles { get; private set; }
        /// <summary>Full and half tiles that are cut to the boundary (counted in FullTiles/HalfTiles too).</summary>
        public int BoundaryTiles { get; private set; }
        public int NonQuadFaces { get; private set; }
        public int ExcludedFaces { get; private set; }
        public int ContinuousJoints { get; private set; }
        public int ShiftedPairs { get; private set; }
        public double Objective { get; private set; }
        public double Bound { get; private set; }
        public double Gap { get; private set; }

        /// <summary>Parsed from <see cref="StatusText"/>.</summary>
        public SolveStatus Status { get; private set; }

        /// <summary>"optimal", "time_limit" or "feasible".</summary>
        public string StatusText { get; private set; }

        public TileDimensions Tile { get; private set; }

        /// <summary>The pattern tiled, without its pairs, every field of it (BoundSource
        /// included; null if the library did not report it).</summary>
        public PatternReport Pattern { get; private set; }

        /// <summary>The joints as laid (after the fit when it ran; the figures before it in
        /// <see cref="JointReport.BeforeFit"/>).</summary>
        public JointReport Joints { get; private set; }

        /// <summary>What the fit stage did; null when it did not run (<see cref="TileOptions.Fit"/> false).</summary>
        public FitReport Fit { get; private set; }

        /// <summary>Boundary cutting and coverage (null if the library did not report it).</summary>
        public CuttingReport Cutting { get; private set; }

        /// <summary>Laying-order summary (null if the library did not report it).</summary>
        public SequenceReport Sequence { get; private set; }

        /// <summary>Seconds of the pattern stage.</summary>
        public double PatternSeconds { get; private set; }

        /// <summary>Seconds of the tile stage (the fit included).</summary>
        public double TileSeconds { get; private set; }

        /// <summary>Seconds of the fit stage (0 when it did not run).</summary>
        public double FitSeconds { get; private set; }

        /// <summary>The JSON text as the library wrote it.</summary>
        public string Json { get; private set; }

        /// <summary>Odd input and results to look at twice (tp_tiles_copy_warning_codes and
        /// tp_tiles_warnings; report.json's "warnings"); empty when all is well.</summary>
        public TilingWarning[] Warnings { get; internal set; }

        /// <summary>Every try of <see cref="TilePatternEngine.Run"/>, in order (report.json's
        /// <c>tries</c>); empty when one try was asked for, and for the stages called one by one
        /// (when more were asked for and a time limit ended the tries, it lists those made).</summary>
        public TryReport[] Tries { get; private set; }

        /// <summary>Which of <see cref="Tries"/> these tiles are, from 0 (report.json's
        /// <c>chosen_try</c>); -1 when <see cref="Tries"/> is empty.</summary>
        public int ChosenTry { get; private set; }

        /// <summary>Reads a report from its JSON (FormatException if it is not JSON).</summary>
        public static Report Parse(string json)
        {
            var root = JsonReader.Parse(json) as Dictionary<string, object>;
            if (root == null)
                throw new FormatException("the report is not a JSON object");
            var r = new Report { Json = json };
            r.Faces = JsonAccess.Integer(root, "faces");
            r.FullTiles = JsonAccess.Integer(root, "full_tiles");
            r.HalfTiles = JsonAccess.Integer(root, "half_tiles");
            r.BoundaryTiles = JsonAccess.Integer(root, "boundary_tiles");
            r.NonQuadFaces = JsonAccess.Integer(root, "non_quad_faces");
            r.ExcludedFaces = JsonAccess.Integer(root, "excluded_faces");
            r.ContinuousJoints = JsonAccess.Integer(root, "continuous_joints");
            r.ShiftedPairs = JsonAccess.Integer(root, "shifted_pairs");
            r.Objective = JsonAccess.Number(root, "objective");
            r.Bound = JsonAccess.Number(root, "bound");
            r.Gap = JsonAccess.Number(root, "gap");
            r.StatusText = JsonAccess.Text(root, "status") ?? "";
            switch (r.StatusText)
            {
                case "optimal": r.Status = SolveStatus.Optimal; break;
                case "time_limit": r.Status = SolveStatus.TimeLimit; break;
                default: r.Status = SolveStatus.Feasible; break;
            }
            var tile = JsonAccess.Object(root, "tile");
            r.Tile = new TileDimensions
            {
                Length = JsonAccess.Number(tile, "length"),
                Width = JsonAccess.Number(tile, "width"),
                Thickness = JsonAccess.Number(tile, "thickness"),
                Joint = JsonAccess.Number(tile, "joint"),
            };
            r.Joints = JointReport.Parse(JsonAccess.Object(root, "joints")) ?? JointReport.Parse(new Dictionary<string, object>());
            r.Fit = FitReport.Parse(JsonAccess.Object(root, "fit"));
            r.Pattern = PatternReport.Parse(JsonAccess.Object(root, "pattern"));
            var cutting = JsonAccess.Object(root, "cutting");
            if (cutting != null)
            {
                var slivers = cutting.ContainsKey("slivers") ? cutting["slivers"] as List<object> : null;
                r.Cutting = new CuttingReport
                {
                    BoundaryTiles = JsonAccess.Integer(cutting, "boundary_tiles"),
                    FillerTiles = JsonAccess.Integer(cutting, "filler_tiles"),
                    TearPieces = JsonAccess.Integer(cutting, "tear_pieces"),
                    TearCuts = JsonAccess.Integer(cutting, "tear_cuts"),
                    TearHalves = JsonAccess.Integer(cutting, "tear_halves"),
                    OutsideTiles = JsonAccess.Integer(cutting, "outside_tiles"),
                    Slivers = slivers == null ? 0 : slivers.Count,
                    BoundaryShapes = JsonAccess.Integer(cutting, "boundary_shapes"),
                    SurfaceArea = JsonAccess.Number(cutting, "surface_area"),
                    TileArea = JsonAccess.Number(cutting, "tile_area"),
                    Coverage = JsonAccess.Number(cutting, "coverage"),
                };
            }
            var sequence = JsonAccess.Object(root, "sequence");
            if (sequence != null)
                r.Sequence = new SequenceReport
                {
                    SupportTiles = JsonAccess.Integer(sequence, "support_tiles"),
                    Unsupported = JsonAccess.Integer(sequence, "unsupported"),
                    SlopedTiles = JsonAccess.Integer(sequence, "sloped_tiles"),
                    ClimbingTiles = JsonAccess.Integer(sequence, "climbing_tiles"),
                    Support = JsonAccess.Text(sequence, "support") ?? "edges",
                };
            var seconds = JsonAccess.Object(root, "seconds");
            r.PatternSeconds = JsonAccess.Number(seconds, "pattern");
            r.TileSeconds = JsonAccess.Number(seconds, "tiles");
            r.FitSeconds = JsonAccess.Number(seconds, "fit");
            var warnings = root.ContainsKey("warnings") ? root["warnings"] as List<object> : null;
            var parsed = new List<TilingWarning>();
            if (warnings != null)
                foreach (object item in warnings)
                {
                    var w = item as Dictionary<string, object>;
                    string name = JsonAccess.Text(w, "code") ?? "";
                    TilingWarningCode code;
                    string pascal = string.Concat(name.Split('_').Where(p => p.Length > 0).Select(p => char.ToUpperInvariant(p[0]) + p.Substring(1)).ToArray());
                    Enum.TryParse(pascal, out code);
                    parsed.Add(new TilingWarning { Code = code, Name = name, Message = JsonAccess.Text(w, "message") ?? "", Face = JsonAccess.Integer(w, "face") });
                }
            r.Warnings = parsed.ToArray();
            var tries = root.ContainsKey("tries") ? root["tries"] as List<object> : null;
            r.Tries = tries == null ? new TryReport[0] : tries.Select(t => TryReport.Parse(t as Dictionary<string, object>)).ToArray();
            r.ChosenTry = root.ContainsKey("chosen_try") ? JsonAccess.Integer(root, "chosen_try") : -1;
            return r;
        }
    }
}

// Options of the three stages in plain .NET types. Each starts from the library's own
// defaults (tp_*_options_init) so the two never drift apart.
using System;
using System.Collections.Generic;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;

namespace TilePattern
{
    /// <summary>The bond the matching aims for (TP_BOND_*).</summary>
    public enum Bond
    {
        /// <summary>Maximum matching, the paper's eq. (1).</summary>
        Stack = 0,
        /// <summary>Staggered, eq. (2): <see cref="PatternOptions.Weight"/> is the penalty per continuous joint.</summary>
        Staggered = 1,
        /// <summary>Running bond, eq. (3): <see cref="PatternOptions.Weight"/> is the reward per shifted pair.</summary>
        RunningBond = 2,
        /// <summary>Herringbone, the 90-degree zig-zag: <see cref="PatternOptions.Weight"/> is the penalty per continuous joint and per pair laid end to end. Needs <see cref="Courses.Free"/>.</summary>
        Herringbone = 3,
        /// <summary>Basket weave, 2 x 2 squares of parallel tiles, alternating: <see cref="PatternOptions.Weight"/> is the penalty per shifted, end-to-end and one-course-apart pair. Needs <see cref="Courses.Free"/>.</summary>
        BasketWeave = 4,
    }

    /// <summary>TP_METHOD_*.</summary>
    public enum SolveMethod
    {
        /// <summary>The fastest route to a proven optimum.</summary>
        Auto = 0,
        /// <summary>The paper's whole program on CBC.</summary>
        Mip = 1,
    }

    /// <summary>TP_FORMULATION_*.</summary>
    public enum Formulation
    {
        /// <summary>The paper's program plus valid rows (same optimum, faster proofs).</summary>
        Strengthened = 0,
        /// <summary>The program exactly as printed in the paper.</summary>
        Paper = 1,
    }

    /// <summary>TP_DIRECTION_*: what the quads are aligned with.</summary>
    public enum FieldDirection
    {
        /// <summary>The principal curvature (the paper's choice).</summary>
        Curvature = 0,
        /// <summary><see cref="RemeshOptions.DirectionVector"/>, projected onto the surface.</summary>
        Vector = 1,
        /// <summary>The curvature field rotated by <see cref="RemeshOptions.AngleDegrees"/>.</summary>
        Angle = 2,
        /// <summary>Nothing: the boundary and smoothness alone orient the quads (the second of
        /// <see cref="TilePatternEngine.Run"/>'s tries). Where the curvature lines converge (a
        /// cone, a funnel, a bend) its quads end fewer rows and the tiles are cut less.</summary>
        Smooth = 3,
    }

    /// <summary>TP_SOLVE_*: how good a pattern is known to be.</summary>
    public enum SolveStatus
    {
        /// <summary>The objective equals the proven bound.</summary>
        Optimal = 0,
        /// <summary>The time limit stopped the search; the pattern is valid, a gap remains.</summary>
        TimeLimit = 1,
        /// <summary>The search ended with a valid pattern and a gap.</summary>
        Feasible = 2,
    }

    /// <summary>TP_BOUND_*: which argument proved a pattern's bound.</summary>
    public enum BoundSource
    {
        /// <summary>A maximum matching bounds the number of tiles.</summary>
        Matching = 0,
        /// <summary>The patch relaxations of a decomposition of the faces (linear or integer).</summary>
        Patches = 1,
        /// <summary>Branch and bound on the whole program.</summary>
        WholeProgram = 2,
        /// <summary>The linear relaxation of the whole program, from its row prices.</summary>
        LinearRelaxation = 3,
    }

    /// <summary>TP_TILE_*.</summary>
    public enum TileKind
    {
        /// <summary>A standard tile over two faces.</summary>
        Full = 0,
        /// <summary>A half tile over one unmatched quad (needs a cut).</summary>
        Half = 1,
        /// <summary>A full or half tile cut to the surface's boundary (see <see cref="Tile.Outline"/>).</summary>
        Boundary = 2,
        /// <summary>A full or half tile cut by the fit stage where it could not be made to fit its
        /// neighbours (labels C1, C2, ...; its <see cref="Tile.Outline"/> is read like a boundary
        /// tile's). A tile cut both to the boundary and by the fit stays <see cref="Boundary"/>.</summary>
        FitCut = 3,
    }

    /// <summary>TP_COURSES_*: which way tiles may lie.</summary>
    public enum Courses
    {
        /// <summary>Either way across any quad (the paper's model; the library's default).</summary>
        Free = 0,
        /// <summary>Every tile along level courses, horizontal with respect to
        /// <see cref="PatternOptions.Up"/>: these fit far better (a 280 x 140 mm tile with a 10 mm
        /// joint turned across its neighbours needs 290 mm where two side by side take 300).
        /// Remesh for them with <see cref="RemeshOptions.ForTile(TileOptions, Courses)"/>.</summary>
        Level = 1,
    }

    /// <summary>Two face indices that form (or must form) one tile.</summary>
    public struct FacePair : IEquatable<FacePair>
    {
        public FacePair(int a, int b)
        {
            A = a;
            B = b;
        }

        public int A { get; private set; }

        public int B { get; private set; }

        public bool Equals(FacePair other) { return A == other.A && B == other.B; }

        public override bool Equals(object obj) { return obj is FacePair && Equals((FacePair)obj); }

        public override int GetHashCode() { return A * 397 ^ B; }

        public override string ToString() { return "[" + A + ", " + B + "]"; }
    }

    /// <summary>Options of the remesh stage (tp_remesh).</summary>
    public sealed class RemeshOptions
    {
        /// <summary>The library's defaults: quads of 0.145 (a 280 mm tile plus a 10 mm joint, halved, in metres) along the curvature.</summary>
        public RemeshOptions()
        {
            Native.EnsureReady();
            LoadDefaults();
        }

        // Separate from the constructor: see Native.EnsureReady.
        [MethodImpl(MethodImplOptions.NoInlining)]
        void LoadDefaults()
        {
            TpRemeshOptions d = NativeMethods.RemeshDefaults();
            TargetEdge = d.target_edge;
            Direction = (FieldDirection)d.direction;
            DirectionVector = new[] { d.direction_x, d.direction_y, d.direction_z };
            AngleDegrees = d.angle_degrees;
            ShapeUp = d.shapeup != 0;
            Creases = d.creases != 0;
            Renormalisation = d.renormalisation;
            TimeLimitSeconds = d.time_limit_seconds;
            FieldWeight = d.field_weight;
            GuideWeight = d.guide_weight;
        }

        /// <summary>Quads whose edge is half a tile plus a joint: (length + joint) / 2.</summary>
        public static RemeshOptions ForTile(TileOptions tile)
        {
            return ForTile(tile, Courses.Free);
        }

        /// <summary>Quads for tiles laid with <paramref name="courses"/>: edge
        /// <see cref="TileOptions.QuadEdge"/>, as the command line's run does.</summary>
        public static RemeshOptions ForTile(TileOptions tile, Courses courses)
        {
            if (tile == null)
                throw new ArgumentNullException("tile");
            return new RemeshOptions { TargetEdge = tile.QuadEdge(courses) };
        }

        /// <summary>Target quad edge in model units.</summary>
        public double TargetEdge { get; set; }

        public FieldDirection Direction { get; set; }

        /// <summary>xyz, used with <see cref="FieldDirection.Vector"/>.</summary>
        public double[] DirectionVector { get; set; }

        /// <summary>Degrees, used with <see cref="FieldDirection.Angle"/>.</summary>
        public double AngleDegrees { get; set; }

        /// <summary>Pull faces towards squares without leaving the surface.</summary>
        public bool ShapeUp { get; set; }

        /// <summary>True (default): each sheet between the creases that part the surface (a
        /// groin vault's webs, split where the faces turn sharply) gets quads of its own, their
        /// field never aligned to the crease; false runs one field over the whole surface. Give
        /// <see cref="TileOptions.Creases"/> the same.</summary>
        public bool Creases { get; set; }

        /// <summary>Strength of the field's renormalising steps, which place its cones and with
        /// them where rows end: any number from 0, default 0.5. Other strengths give other,
        /// equally valid quads whose tiles may fit better; the command line's <c>run</c> tries
        /// 0.5, 1 and 0.25 and keeps the tiles with the fewest cuts and the closest joints.</summary>
        public double Renormalisation { get; set; }

        /// <summary>Wall-clock limit of the stage in seconds (default 60): when it passes, the quad
        /// mesh as it stands is returned if one exists, otherwise a <see cref="SolverTimeLimitException"/>.</summary>
        public double TimeLimitSeconds { get; set; }

        /// <summary>The designer's direction field (e.g. principal stress or thrust directions):
        /// one xyz vector per vertex or one per face of the surface, told apart by the count;
        /// null (default) for none. Signs and lengths do not matter; NaN, infinite or zero
        /// vectors are refused with their index.</summary>
        public double[][] Field { get; set; }

        /// <summary>Share of <see cref="Field"/> against the curvature field (or
        /// <see cref="Direction"/>), from 0 to 1; default 1 (the field alone).</summary>
        public double FieldWeight { get; set; }

        /// <summary><see cref="Field"/> as 3 n doubles, or null.</summary>
        internal double[] FlatField()
        {
            if (Field == null)
                return null;
            var flat = new double[3 * Field.Length];
            for (int i = 0; i < Field.Length; i++)
            {
                double[] v = Field[i];
                if (v == null || v.Length != 3)
                    throw new ArgumentException("Field[" + i + "] must be 3 numbers (x, y, z)", "Field");
                flat[3 * i] = v[0];
                flat[3 * i + 1] = v[1];
                flat[3 * i + 2] = v[2];
            }
            return flat;
        }

        /// <summary>Guide curves the quad rows follow near them (within 2 target edges, falling
        /// off): polylines in model units, each an array of at least 2 xyz points
        /// (<c>Guides[curve][point] = {x, y, z}</c>), on or near the surface; null (default)
        /// for none. Curves with too few points, NaN or infinite coordinates, no length or
        /// nowhere near the surface are refused with their index.</summary>
        public double[][][] Guides { get; set; }

        /// <summary>Share of <see cref="Guides"/> on the curves against every other source
        /// (curvature, <see cref="Direction"/>, <see cref="Field"/>), from 0 to 1; default 1
        /// (the guides alone on them).</summary>
        public double GuideWeight { get; set; }

        /// <summary><see cref="Guides"/> as 3 n doubles (every curve's points one after the
        /// other) and the number of points of each curve, or nulls.</summary>
        internal void FlatGuides(out double[] points, out uint[] sizes)
        {
            points = null;
            sizes = null;
            if (Guides == null || Guides.Length == 0)
                return;
            int total = 0;
            for (int c = 0; c < Guides.Length; c++)
            {
                if (Guides[c] == null)
                    throw new ArgumentException("Guides[" + c + "] is null; every curve is an array of xyz points", "Guides");
                total += Guides[c].Length;
            }
            points = new double[3 * total];
            sizes = new uint[Guides.Length];
            int k = 0;
            for (int c = 0; c < Guides.Length; c++)
            {
                sizes[c] = (uint)Guides[c].Length;
                for (int i = 0; i < Guides[c].Length; i++, k++)
                {
                    double[] p = Guides[c][i];
                    if (p == null || p.Length != 3)
                        throw new ArgumentException("Guides[" + c + "][" + i + "] must be 3 numbers (x, y, z)", "Guides");
                    points[3 * k] = p[0];
                    points[3 * k + 1] = p[1];
                    points[3 * k + 2] = p[2];
                }
            }
        }

        [MethodImpl(MethodImplOptions.NoInlining)]
        internal TpRemeshOptions ToNative()
        {
            TpRemeshOptions o = NativeMethods.RemeshDefaults();
            // The size of the struct as this wrapper knows it, not as the library does.
            o.struct_size = (uint)Marshal.SizeOf(typeof(TpRemeshOptions));
            o.target_edge = TargetEdge;
            o.direction = (int)Direction;
            Xyz.Read(DirectionVector, "DirectionVector", ref o.direction_x, ref o.direction_y, ref o.direction_z);
            o.angle_degrees = AngleDegrees;
            o.shapeup = ShapeUp ? 1 : 0;
            o.creases = Creases ? 1 : 0;
            o.renormalisation = Renormalisation;
            o.time_limit_seconds = TimeLimitSeconds;
            o.field_weight = FieldWeight;
            o.guide_weight = GuideWeight;
            // field_vectors, field_count and the guides' arrays and counts are set by the
            // caller around the pinned arrays.
            return o;
        }
    }

    /// <summary>Options of the pattern stage (tp_pattern_solve).</summary>
    public sealed class PatternOptions
    {
        /// <summary>The library's defaults: staggered, weight 0.5, 60 s, auto, strengthened.</summary>
        public PatternOptions()
        {
            Native.EnsureReady();
            LoadDefaults();
        }

        [MethodImpl(MethodImplOptions.NoInlining)]
        void LoadDefaults()
        {
            TpPatternOptions d = NativeMethods.PatternDefaults();
            Bond = (Bond)d.bond;
            Weight = d.weight;
            TimeLimitSeconds = d.time_limit_seconds;
            Gap = d.gap;
            Method = (SolveMethod)d.method;
            Formulation = (Formulation)d.formulation;
            ForcedPairs = new List<FacePair>();
            ExcludedFaces = new List<int>();
            Courses = (Courses)d.courses;
            Up = new[] { d.up_x, d.up_y, d.up_z };
        }

        public Bond Bond { get; set; }

        /// <summary>Weight of the bond term (w or w_R).</summary>
        public double Weight { get; set; }

        /// <summary>Wall-clock limit in seconds; 0 returns the greedy start at once.</summary>
        public double TimeLimitSeconds { get; set; }

        /// <summary>Relative gap at which the search stops: once (bound - objective) / bound is
        /// at most this (like a MIP solver's gap), from 0 (default: prove optimality or reach the
        /// time limit) to 1.</summary>
        public double Gap { get; set; }

        public SolveMethod Method { get; set; }

        public Formulation Formulation { get; set; }

        /// <summary>Pairs of adjacent quads that must become tiles.</summary>
        public IList<FacePair> ForcedPairs { get; set; }

        /// <summary>Faces that take part in no tile (openings, areas laid by hand).</summary>
        public IList<int> ExcludedFaces { get; set; }

        /// <summary>Which way tiles may lie: <see cref="TilePattern.Courses.Free"/> (default, the
        /// paper's model) or all along level courses (<see cref="TilePattern.Courses.Level"/>).</summary>
        public Courses Courses { get; set; }

        /// <summary>Up direction of level courses, xyz; default (0, 0, 1).</summary>
        public double[] Up { get; set; }

        /// <summary>Zones: a bond per face of the quad mesh, in face order (e.g. a band of
        /// <see cref="TilePattern.Bond.Herringbone"/> in a staggered vault); a null item lays its
        /// face in <see cref="Bond"/>, every zone at <see cref="Weight"/>. Null (default): every
        /// face in <see cref="Bond"/>. Its length must be the mesh's face count; a herringbone or
        /// basket-weave zone needs <see cref="TilePattern.Courses.Free"/>.</summary>
        public Bond?[] Zones { get; set; }

        /// <summary><see cref="Zones"/> as TP_BOND_* codes (TP_ZONE_DEFAULT, -1, for null
        /// items), or null for none.</summary>
        internal int[] ZoneCodes()
        {
            if (Zones == null)
                return null;
            if (Zones.Length == 0)
                throw new ArgumentException("Zones must give one bond per face, or be null for none", "Zones");
            var codes = new int[Zones.Length];
            for (int k = 0; k < Zones.Length; k++)
                codes[k] = Zones[k].HasValue ? (int)Zones[k].Value : NativeMethods.TP_ZONE_DEFAULT;
            return codes;
        }

        /// <summary>The native struct, its arrays flattened into <paramref name="forced"/> and
        /// <paramref name="excluded"/>; the caller pins them and fills in the pointers.</summary>
        [MethodImpl(MethodImplOptions.NoInlining)]
        internal TpPatternOptions ToNative(out uint[] forced, out uint[] excluded)
        {
            TpPatternOptions o = NativeMethods.PatternDefaults();
            o.struct_size = (uint)Marshal.SizeOf(typeof(TpPatternOptions));
            o.bond = (int)Bond;
            o.weight = Weight;
            o.time_limit_seconds = TimeLimitSeconds;
            o.gap = Gap;
            o.method = (int)Method;
            o.formulation = (int)Formulation;
            o.courses = (int)Courses;
            Xyz.Read(Up, "Up", ref o.up_x, ref o.up_y, ref o.up_z);
            var pairs = ForcedPairs ?? new List<FacePair>();
            forced = new uint[2 * pairs.Count];
            for (int k = 0; k < pairs.Count; k++)
            {
                forced[2 * k] = FaceIndex(pairs[k].A, "ForcedPairs");
                forced[2 * k + 1] = FaceIndex(pairs[k].B, "ForcedPairs");
            }
            var faces = ExcludedFaces ?? new List<int>();
            excluded = new uint[faces.Count];
            for (int k = 0; k < faces.Count; k++)
                excluded[k] = FaceIndex(faces[k], "ExcludedFaces");
            o.forced_pairs = IntPtr.Zero;
            o.forced_pair_count = Native.Size(pairs.Count);
            o.excluded_faces = IntPtr.Zero;
            o.excluded_face_count = Native.Size(faces.Count);
            return o;
        }

        static uint FaceIndex(int face, string what)
        {
            if (face < 0)
                throw new ArgumentOutOfRangeException(what, face, "face indices are 0-based and not negative");
            return (uint)face;
        }
    }

    /// <summary>Tile dimensions in model units, and the cutting and laying-order settings
    /// (tp_tiles_build / tp_tiles_build_on_surface).</summary>
    public sealed class TileOptions
    {
        /// <summary>The library's defaults: 0.28 x 0.14 x 0.015 with a 0.01 joint (metres).</summary>
        public TileOptions()
        {
            Native.EnsureReady();
            LoadDefaults();
        }

        [MethodImpl(MethodImplOptions.NoInlining)]
        void LoadDefaults()
        {
            TpTileOptions d = NativeMethods.TileDefaults();
            Length = d.length;
            Width = d.width;
            Thickness = d.thickness;
            Joint = d.joint;
            CutTolerance = d.cut_tolerance;
            MinKeptWidth = d.min_kept_width;
            Up = new[] { d.up_x, d.up_y, d.up_z };
            SupportBand = d.support_band;
            Fit = d.fit != 0;
            FitTimeLimitSeconds = d.fit_time_limit_seconds;
            OverlapTolerance = d.fit_overlap_tolerance;
            BondTolerance = d.fit_bond_tolerance;
            UnitsPerMm = d.units_per_mm;
            Creases = d.creases != 0;
        }

        public double Length { get; set; }

        public double Width { get; set; }

        public double Thickness { get; set; }

        /// <summary>Mortar joint.</summary>
        public double Joint { get; set; }

        /// <summary>Tiles the boundary enters by no more than this stay whole; cut shapes this
        /// close share a cut-list label. Negative (default): 1 % of the width.</summary>
        public double CutTolerance { get; set; }

        /// <summary>Boundary pieces narrower than this are slivers: reported, not emitted.
        /// Negative (default): a fifth of the width.</summary>
        public double MinKeptWidth { get; set; }

        /// <summary>Up direction for the laying order, xyz; default (0, 0, 1).</summary>
        public double[] Up { get; set; }

        /// <summary>Tiles with a boundary edge within this height of the lowest boundary point
        /// stand on the supports. Negative (default): one tile width.</summary>
        public double SupportBand { get; set; }

        /// <summary>True (default): the fit stage moves the tiles on the surface so that their
        /// joints come close to <see cref="Joint"/>, keeping the bond, and cuts what cannot fit
        /// (<see cref="TileKind.FitCut"/>); false keeps the paper's placement (section 3.5) and the
        /// report has no <see cref="Report.Fit"/>.</summary>
        public bool Fit { get; set; }

        /// <summary>Wall-clock limit of the fit in seconds (default 10); when it passes the best
        /// placement so far is kept (<see cref="FitStatus.TimeLimit"/>). The same limit holds
        /// again for filling the fit's tears with pieces (those laid so far are kept). It also
        /// sizes, by a count of work and not the clock, the largest first placement a second
        /// one (with closers) may follow, so the same input gives the same tiles on any
        /// machine.</summary>
        public double FitTimeLimitSeconds { get; set; }

        /// <summary>Overlaps the fit may leave; deeper ones are cut. Negative (default): a
        /// twentieth of the joint, at least a three-hundredth of the tile's width.</summary>
        public double OverlapTolerance { get; set; }

        /// <summary>How far the fit may move a running bond's half offset or an aligned joint.
        /// Negative (default): a tenth of the tile length.</summary>
        public double BondTolerance { get; set; }

        /// <summary>Model units per millimetre, for the report's shares of joints within 2 and
        /// 5 mm: 0.001 (default) for a model in metres, 1 in millimetres
        /// (<see cref="TileDefaults.UnitsPerMm"/> gives it for a document's units).</summary>
        public double UnitsPerMm { get; set; }

        /// <summary>True (default): tiles are cut to the creases that part the surface into
        /// sheets, half a joint short on each side, and tiles and filler pieces stay on their own
        /// sheet; false takes the surface as one sheet. Give <see cref="RemeshOptions.Creases"/>
        /// the same.</summary>
        public bool Creases { get; set; }

        /// <summary>The quad edge to remesh with: (length + joint) / 2, the paper's choice, for
        /// <see cref="Courses.Free"/>; for <see cref="Courses.Level"/> at least a course's height,
        /// width + joint, since no placement can change the quads' height across the courses (the
        /// fit then closes the head joints along each course).</summary>
        public double QuadEdge(Courses courses)
        {
            return QuadEdgeOf(Length, Width, Joint, courses);
        }

        /// <summary><see cref="QuadEdge"/> for a tile of these dimensions (model units).</summary>
        public static double QuadEdgeOf(double length, double width, double joint, Courses courses)
        {
            double edge = (length + joint) / 2.0;
            return courses == Courses.Level ? Math.Max(edge, width + joint) : edge;
        }

        [MethodImpl(MethodImplOptions.NoInlining)]
        internal TpTileOptions ToNative()
        {
            TpTileOptions o = NativeMethods.TileDefaults();
            o.struct_size = (uint)Marshal.SizeOf(typeof(TpTileOptions));
            o.length = Length;
            o.width = Width;
            o.thickness = Thickness;
            o.joint = Joint;
            o.cut_tolerance = CutTolerance;
            o.min_kept_width = MinKeptWidth;
            Xyz.Read(Up, "Up", ref o.up_x, ref o.up_y, ref o.up_z);
            o.support_band = SupportBand;
            o.fit = Fit ? 1 : 0;
            o.fit_time_limit_seconds = FitTimeLimitSeconds;
            o.fit_overlap_tolerance = OverlapTolerance;
            o.fit_bond_tolerance = BondTolerance;
            o.units_per_mm = UnitsPerMm;
            o.creases = Creases ? 1 : 0;
            return o;
        }
    }

    /// <summary>Options of <see cref="TilePatternEngine.Run"/> beyond those of the three stages
    /// (tp_run's TpRunOptions).</summary>
    public sealed class RunOptions
    {
        /// <summary>The most quad meshes a run carries through to tiles: the remesh options'
        /// <see cref="RemeshOptions.Renormalisation"/>, a smooth field at it (following neither the
        /// curvature nor anything else; made only when no direction, angle, designer's field or
        /// guide curves are given), then twice and half the strength.</summary>
        public const int MaxTries = 6;

        /// <summary>The library's defaults: <see cref="Tries"/> 0 (automatic).</summary>
        public RunOptions()
        {
            Native.EnsureReady();
            LoadDefaults();
        }

        [MethodImpl(MethodImplOptions.NoInlining)]
        void LoadDefaults()
        {
            TpRunOptions d = NativeMethods.RunDefaults();
            Tries = checked((int)d.tries);
        }

        /// <summary>How many quad meshes of the surface to carry through the pattern, the tiles
        /// and the fit, keeping the tiles that fit best: 0 (default) for the command line's
        /// choice (all when the surface needs at most 10,000 quads of
        /// <see cref="RemeshOptions.TargetEdge"/>, else 1), or 1 to <see cref="MaxTries"/>
        /// (the strength <see cref="RemeshOptions.Renormalisation"/>, the smooth field at it, then
        /// twice and half the strength, then the smooth field's quads laid out for level courses,
        /// then the smooth field free of the boundary (made only where the first try follows an
        /// edge with corners), in this order; <see cref="TryReport.Field"/>,
        /// <see cref="TryReport.QuadsAlongCourses"/> and <see cref="TryReport.BoundaryFree"/>
        /// name each). 1 gives what <see cref="TilePatternEngine.Remesh"/>,
        /// <see cref="TilePatternEngine.Match"/> and <see cref="TilePatternEngine.Tiles(Pattern, TileOptions, PolyMesh)"/>
        /// give one by one. Anything else throws <see cref="ArgumentOutOfRangeException"/>
        /// when the run starts.</summary>
        public int Tries { get; set; }

        [MethodImpl(MethodImplOptions.NoInlining)]
        internal TpRunOptions ToNative()
        {
            if (Tries < 0 || Tries > MaxTries)
                throw new ArgumentOutOfRangeException("Tries", Tries, "Tries is 0 (automatic: all on a surface of at most 10,000 quads, else 1) or 1 to " + MaxTries + ", not " + Tries);
            TpRunOptions o = NativeMethods.RunDefaults();
            o.struct_size = (uint)Marshal.SizeOf(typeof(TpRunOptions));
            o.tries = (uint)Tries;
            return o;
        }
    }

    /// <summary>Vectors given as xyz arrays.</summary>
    internal static class Xyz
    {
        /// <summary>Copies <paramref name="v"/> (3 values) into x, y, z; a null array leaves them
        /// as they are (the library's default).</summary>
        internal static void Read(double[] v, string name, ref double x, ref double y, ref double z)
        {
            if (v == null)
                return;
            if (v.Length != 3)
                throw new ArgumentException(name + " needs 3 values (xyz), not " + v.Length, name);
            x = v[0];
            y = v[1];
            z = v[2];
        }
    }
}

// P/Invoke declarations for every export of include/tilepattern.h (TP_ABI_VERSION 9: tp_run,
// the whole pipeline with tries, and TpRunOptions; 8 the field's renormalisation strength; 7
// the creases switch; 6 guide curves and zones; 5 the designer's field, 4 the gap, 3 the fit stage and level courses; 2
// added boundary tiles and the tp_*_options_init functions), and
// mirrors of its structs. Nothing here is public: the public API is TilePatternEngine.
//
// C to C# type map: size_t -> UIntPtr, uint32_t -> uint, int32_t / TpStatus -> int,
// double -> double, const char* returned -> IntPtr (static string, never freed by us),
// opaque handles -> SafeHandle subclasses (NativeHandles.cs), out pointers -> out.
// tp_test_panic exists only in a build with the test-panic feature: it is declared in the
// test assembly, not here.
using System;
using System.Runtime.InteropServices;

namespace TilePattern
{
    /// <summary>TpProgressCallback: return non-zero to cancel. Runs on the calling thread.</summary>
    [UnmanagedFunctionPointer(CallingConvention.Cdecl)]
    internal delegate int TpProgressCallback(IntPtr user, uint stage, double fraction);

    /// <summary>Mirror of TpPatternOptions (120 bytes on 64-bit targets; 104 before ABI 6, 96
    /// before ABI 4, 64 before ABI 3);
    /// <c>double up[3]</c> is spelled as three doubles.</summary>
    [StructLayout(LayoutKind.Sequential)]
    internal struct TpPatternOptions
    {
        public uint struct_size;
        public int bond;
        public double weight;
        public double time_limit_seconds;
        public int method;
        public int formulation;
        public IntPtr forced_pairs;          // const uint32_t*
        public UIntPtr forced_pair_count;    // size_t
        public IntPtr excluded_faces;        // const uint32_t*
        public UIntPtr excluded_face_count;  // size_t
        // Since ABI 3.
        public int courses;
        public double up_x;
        public double up_y;
        public double up_z;
        // Since ABI 4.
        public double gap;
        // Since ABI 6.
        public IntPtr zones;                 // const int32_t*
        public UIntPtr zone_count;           // size_t
    }

    /// <summary>Mirror of TpPatternSummary (96 bytes on 64-bit targets).</summary>
    [StructLayout(LayoutKind.Sequential)]
    internal struct TpPatternSummary
    {
        public UIntPtr faces;
        public UIntPtr pairs;
        public UIntPtr unpaired;
        public UIntPtr excluded;
        public UIntPtr non_quad;
        public UIntPtr continuous_joints;
        public UIntPtr shifted_pairs;
        public double objective;
        public double bound;
        public double gap;
        public double seconds;
        public int status;
    }

    /// <summary>Mirror of TpRemeshOptions (152 bytes on 64-bit targets; 144 before ABI 8, 136 before ABI 7, 96 before ABI 6, 72 before ABI 5). The C array
    /// <c>double direction_vector[3]</c> is spelled as three doubles, which has the same
    /// layout and keeps the struct blittable.</summary>
    [StructLayout(LayoutKind.Sequential)]
    internal struct TpRemeshOptions
    {
        public uint struct_size;
        public double target_edge;
        public int direction;
        public double direction_x;
        public double direction_y;
        public double direction_z;
        public double angle_degrees;
        public int shapeup;
        public double time_limit_seconds;
        public IntPtr field_vectors;
        public UIntPtr field_count;
        public double field_weight;
        // Since ABI 6: guide curves.
        public IntPtr guide_points;
        public UIntPtr guide_point_count;
        public IntPtr guide_curve_sizes;
        public UIntPtr guide_count;
        public double guide_weight;
        // Since ABI 7: split at the creases.
        public int creases;
        // Since ABI 8: the strength that places the field's cones.
        public double renormalisation;
    }

    /// <summary>Mirror of TpTileOptions (136 bytes; 128 before ABI 7, 88 before ABI 3); <c>double up[3]</c> is
    /// spelled as three doubles.</summary>
    [StructLayout(LayoutKind.Sequential)]
    internal struct TpTileOptions
    {
        public uint struct_size;
        public double length;
        public double width;
        public double thickness;
        public double joint;
        public double cut_tolerance;
        public double min_kept_width;
        public double up_x;
        public double up_y;
        public double up_z;
        public double support_band;
        // Since ABI 3: the fit stage.
        public int fit;
        public double fit_time_limit_seconds;
        public double fit_overlap_tolerance;
        public double fit_bond_tolerance;
        public double units_per_mm;
        // Since ABI 7: cut to the creases.
        public int creases;
    }

    /// <summary>Mirror of TpRunOptions (8 bytes; since ABI 9): the options of tp_run beyond
    /// those of the three stages.</summary>
    [StructLayout(LayoutKind.Sequential)]
    internal struct TpRunOptions
    {
        public uint struct_size;
        public uint tries;
    }

    // Return buffers of the tp_*_options_default() functions. These return their struct by
    // value, which every 64-bit C ABI does through a caller-allocated buffer (the structs are
    // larger than 16 bytes and start with a uint32, so they are never returned in registers).
    // A newer library whose options struct has grown (the struct_size scheme allows that)
    // would write its larger struct past a buffer of the size this wrapper knows, so the
    // buffer is made 512 bytes and only the known prefix is read.
    [StructLayout(LayoutKind.Sequential, Size = 512)]
    internal struct TpPatternOptionsReturn
    {
        public TpPatternOptions value;
    }

    [StructLayout(LayoutKind.Sequential, Size = 512)]
    internal struct TpRemeshOptionsReturn
    {
        public TpRemeshOptions value;
    }

    [StructLayout(LayoutKind.Sequential, Size = 512)]
    internal struct TpTileOptionsReturn
    {
        public TpTileOptions value;
    }

    internal static class NativeMethods
    {
        internal const string Library = "tilepattern";

        // The header's #defines.
        internal const int TP_ABI_VERSION = 10;
        internal const uint TP_STAGE_REMESH = 1;
        internal const uint TP_STAGE_PATTERN = 2;
        internal const uint TP_STAGE_TILES = 3;
        internal const uint TP_STAGE_RUN = 4;
        internal const int TP_BOND_STACK = 0;
        internal const int TP_BOND_STAGGERED = 1;
        internal const int TP_BOND_RUNNING = 2;
        internal const int TP_BOND_HERRINGBONE = 3;
        internal const int TP_BOND_BASKET_WEAVE = 4;
        internal const int TP_ZONE_DEFAULT = -1;
        internal const int TP_METHOD_AUTO = 0;
        internal const int TP_METHOD_MIP = 1;
        internal const int TP_FORMULATION_STRENGTHENED = 0;
        internal const int TP_FORMULATION_PAPER = 1;
        internal const int TP_SOLVE_OPTIMAL = 0;
        internal const int TP_SOLVE_TIME_LIMIT = 1;
        internal const int TP_SOLVE_FEASIBLE = 2;
        internal const int TP_BOUND_MATCHING = 0;
        internal const int TP_BOUND_PATCHES = 1;
        internal const int TP_BOUND_WHOLE_PROGRAM = 2;
        internal const int TP_BOUND_LINEAR_RELAXATION = 3;
        internal const int TP_COURSES_FREE = 0;
        internal const int TP_COURSES_LEVEL = 1;
        internal const int TP_DIRECTION_CURVATURE = 0;
        internal const int TP_DIRECTION_VECTOR = 1;
        internal const int TP_DIRECTION_ANGLE = 2;
        internal const int TP_DIRECTION_SMOOTH = 3;
        internal const int TP_TILE_FULL = 0;
        internal const int TP_TILE_HALF = 1;
        internal const int TP_TILE_BOUNDARY = 2;
        internal const int TP_TILE_FIT_CUT = 3;
        internal const uint TP_NO_FACE = uint.MaxValue;

        // A safety net only: the public API calls Native.EnsureReady() before any P/Invoke.
        // (Mono binds a P/Invoke when it compiles the caller, before this would run.)
        static NativeMethods()
        {
            NativeLibraryLoader.EnsureLoaded();
        }

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern IntPtr tp_version();

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern uint tp_abi_version();

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_mesh_new(
            double[] vertices, UIntPtr vertex_count,
            uint[] face_indices, UIntPtr index_count,
            uint[] face_sizes, UIntPtr face_count,
            out MeshHandle mesh);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_mesh_new_welded(
            double[] vertices, UIntPtr vertex_count,
            uint[] face_indices, UIntPtr index_count,
            uint[] face_sizes, UIntPtr face_count,
            double relative_tolerance,
            out MeshHandle mesh);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_mesh_copy_sources(MeshHandle mesh, [Out] uint[] vertex_source, UIntPtr vertex_capacity,
            [Out] uint[] face_source, UIntPtr face_capacity);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern void tp_mesh_free(IntPtr mesh);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_mesh_counts(MeshHandle mesh, out UIntPtr vertex_count, out UIntPtr face_count, out UIntPtr index_count);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_mesh_copy_vertices(MeshHandle mesh, [Out] double[] output, UIntPtr capacity);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_mesh_copy_faces(MeshHandle mesh, [Out] uint[] indices, UIntPtr index_capacity, [Out] uint[] sizes, UIntPtr size_capacity);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern TpPatternOptionsReturn tp_pattern_options_default();

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_pattern_options_init(ref TpPatternOptions options, UIntPtr size);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_pattern_solve(MeshHandle mesh, ref TpPatternOptions options, TpProgressCallback progress, IntPtr user, out PatternHandle pattern);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern void tp_pattern_free(IntPtr pattern);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_pattern_summary(PatternHandle pattern, out TpPatternSummary summary);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_pattern_bound_source(PatternHandle pattern, out int source);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_pattern_copy_pairs(PatternHandle pattern, [Out] uint[] output, UIntPtr capacity);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_pattern_copy_unpaired(PatternHandle pattern, [Out] uint[] output, UIntPtr capacity);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern TpRemeshOptionsReturn tp_remesh_options_default();

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_remesh_options_init(ref TpRemeshOptions options, UIntPtr size);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_remesh(MeshHandle mesh, ref TpRemeshOptions options, TpProgressCallback progress, IntPtr user, out MeshHandle quads);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern UIntPtr tp_last_error_message([Out] byte[] buffer, UIntPtr length);

        // TpRunOptions is 8 bytes, which the 64-bit C ABIs return in a register, not through
        // a caller's buffer: a 512-byte return buffer as above would be the wrong calling
        // convention, so this one returns the struct itself. The wrapper never calls it (only
        // the layout tests do): it initialises with tp_run_options_init, which is safe whatever
        // the loaded library's struct size.
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern TpRunOptions tp_run_options_default();

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_run_options_init(ref TpRunOptions options, UIntPtr size);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_run(MeshHandle surface, ref TpRemeshOptions remesh, ref TpPatternOptions pattern, ref TpTileOptions tiles,
            ref TpRunOptions run, TpProgressCallback progress, IntPtr user, out MeshHandle out_quads, out PatternHandle out_pattern, out TilesHandle out_tiles);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern TpTileOptionsReturn tp_tile_options_default();

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_tile_options_init(ref TpTileOptions options, UIntPtr size);

        // Defaults through the tp_*_options_init functions, which write no more than the
        // struct this wrapper knows, whatever the loaded library's version.
        [System.Runtime.CompilerServices.MethodImpl(System.Runtime.CompilerServices.MethodImplOptions.NoInlining)]
        internal static TpPatternOptions PatternDefaults()
        {
            var o = new TpPatternOptions();
            Initialised(tp_pattern_options_init(ref o, (UIntPtr)Marshal.SizeOf(typeof(TpPatternOptions))));
            return o;
        }

        [System.Runtime.CompilerServices.MethodImpl(System.Runtime.CompilerServices.MethodImplOptions.NoInlining)]
        internal static TpRemeshOptions RemeshDefaults()
        {
            var o = new TpRemeshOptions();
            Initialised(tp_remesh_options_init(ref o, (UIntPtr)Marshal.SizeOf(typeof(TpRemeshOptions))));
            return o;
        }

        [System.Runtime.CompilerServices.MethodImpl(System.Runtime.CompilerServices.MethodImplOptions.NoInlining)]
        internal static TpTileOptions TileDefaults()
        {
            var o = new TpTileOptions();
            Initialised(tp_tile_options_init(ref o, (UIntPtr)Marshal.SizeOf(typeof(TpTileOptions))));
            return o;
        }

        [System.Runtime.CompilerServices.MethodImpl(System.Runtime.CompilerServices.MethodImplOptions.NoInlining)]
        internal static TpRunOptions RunDefaults()
        {
            var o = new TpRunOptions();
            Initialised(tp_run_options_init(ref o, (UIntPtr)Marshal.SizeOf(typeof(TpRunOptions))));
            return o;
        }

        static void Initialised(int status)
        {
            if (status != 0)
                throw new InvalidOperationException("initialising native options failed with status " + status);
        }

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_tiles_build(MeshHandle mesh, PatternHandle pattern, ref TpTileOptions options, out TilesHandle tiles);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_tiles_build_on_surface(MeshHandle mesh, PatternHandle pattern, MeshHandle surface, ref TpTileOptions options, out TilesHandle tiles);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_tiles_build_with_progress(MeshHandle mesh, PatternHandle pattern, MeshHandle surface, ref TpTileOptions options,
            TpProgressCallback progress, IntPtr user, out TilesHandle tiles);

        /// <summary>tp_tiles_build_with_progress with surface = NULL (a SafeHandle parameter cannot be null).</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, EntryPoint = "tp_tiles_build_with_progress")]
        internal static extern int tp_tiles_build_with_progress_without_surface(MeshHandle mesh, PatternHandle pattern, IntPtr surface, ref TpTileOptions options,
            TpProgressCallback progress, IntPtr user, out TilesHandle tiles);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_tiles_copy_joint_deviations(TilesHandle tiles, [Out] double[] output, UIntPtr capacity);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern void tp_tiles_free(IntPtr tiles);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_tiles_count(TilesHandle tiles, out UIntPtr count);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_tiles_copy_kinds(TilesHandle tiles, [Out] int[] output, UIntPtr capacity);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_tiles_copy_corners(TilesHandle tiles, [Out] double[] output, UIntPtr capacity);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_tiles_copy_frames(TilesHandle tiles, [Out] double[] output, UIntPtr capacity);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_tiles_copy_sizes(TilesHandle tiles, [Out] double[] output, UIntPtr capacity);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_tiles_copy_faces(TilesHandle tiles, [Out] uint[] output, UIntPtr capacity);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_tiles_report_json(TilesHandle tiles, [Out] byte[] buffer, UIntPtr length, out UIntPtr needed);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_tiles_copy_steps(TilesHandle tiles, [Out] uint[] output, UIntPtr capacity);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_tiles_copy_kept_fractions(TilesHandle tiles, [Out] double[] output, UIntPtr capacity);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_tiles_outline_counts(TilesHandle tiles, out UIntPtr loops, out UIntPtr points);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_tiles_copy_loop_counts(TilesHandle tiles, [Out] uint[] output, UIntPtr capacity);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_tiles_copy_loop_sizes(TilesHandle tiles, [Out] uint[] output, UIntPtr capacity);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_tiles_copy_loop_points(TilesHandle tiles, [Out] double[] output, UIntPtr capacity);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_tiles_labels(TilesHandle tiles, [Out] byte[] buffer, UIntPtr length, out UIntPtr needed);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_tiles_cutlist_json(TilesHandle tiles, [Out] byte[] buffer, UIntPtr length, out UIntPtr needed);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_tiles_warning_count(TilesHandle tiles, out UIntPtr count);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_tiles_copy_warning_codes(TilesHandle tiles, [Out] int[] output, UIntPtr capacity);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        internal static extern int tp_tiles_warnings(TilesHandle tiles, [Out] byte[] buffer, UIntPtr length, out UIntPtr needed);
    }
}

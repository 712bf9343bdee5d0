// The public entry points: remesh -> match -> tiles (+ report), and the three in one run with tries.
using System;
using System.Collections.Generic;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
using System.Text;
using System.Threading;

namespace TilePattern
{
    // Every public method here first calls Native.EnsureReady() and leaves the P/Invokes to a
    // [NoInlining] helper: Mono binds a P/Invoke when it compiles the method that calls it, so
    // that method must be compiled after the loader has run (see NativeLibraryLoader).

    /// <summary>The three stages of the TilePattern library. Every method is thread-safe in
    /// the sense that calls on different threads do not interfere; progress is reported and
    /// cancellation polled on the calling thread. Failures throw a
    /// <see cref="TilePatternException"/> subclass (or <see cref="TilePatternCanceledException"/>).</summary>
    public static class TilePatternEngine
    {
        /// <summary>The ABI version this wrapper was written for (TP_ABI_VERSION).</summary>
        public const int AbiVersion = NativeMethods.TP_ABI_VERSION;

        /// <summary>Names the native library file to load, or a folder holding it (directly or
        /// under runtimes/&lt;rid&gt;/native/); overrides TILEPATTERN_LIB. For hosts that load
        /// TilePattern.dll from bytes, where its own folder is unknown. Call it before anything
        /// else: it returns false, and does nothing, once the library has been looked for.</summary>
        public static bool UseNativeLibrary(string path)
        {
            return NativeLibraryLoader.SetExplicitPath(path);
        }

        /// <summary>Where the native library was loaded from (null: found by the runtime's own search).</summary>
        public static string NativeLibraryPath
        {
            get
            {
                Native.EnsureReady();
                return NativeLibraryLoader.LoadedPath;
            }
        }

        /// <summary>What the loader tried, for error reports.</summary>
        public static string NativeLibraryDescription
        {
            get { return NativeLibraryLoader.Description; }
        }

        /// <summary>The native library's version, e.g. "0.1.0".</summary>
        public static string NativeVersion
        {
            get
            {
                Native.EnsureReady();
                return Native.Version();
            }
        }

        /// <summary>TP_ABI_VERSION of the library actually loaded.</summary>
        public static int NativeAbiVersion
        {
            get
            {
                NativeLibraryLoader.EnsureLoaded();
                return (int)Native.AbiVersion();
            }
        }

        /// <summary>Throws <see cref="InvalidMeshException"/> if the library refuses the mesh.</summary>
        public static void Validate(PolyMesh mesh)
        {
            if (mesh == null)
                throw new ArgumentNullException("mesh");
            Native.EnsureReady();
            mesh.CreateHandle().Dispose();
        }

        /// <summary>Stage 1: quadrangulates a triangle or polygon surface into near-square quads.
        /// The library reports progress throughout the stage (about every 10 ms) and stops soon
        /// after the token is cancelled (<see cref="TilePatternCanceledException"/>).</summary>
        public static PolyMesh Remesh(PolyMesh surface, RemeshOptions options = null, IProgress<double> progress = null,
            CancellationToken cancellationToken = default(CancellationToken))
        {
            if (surface == null)
                throw new ArgumentNullException("surface");
            Native.EnsureReady();
            return RemeshCore(surface, options ?? new RemeshOptions(), progress, cancellationToken);
        }

        [MethodImpl(MethodImplOptions.NoInlining)]
        static PolyMesh RemeshCore(PolyMesh surface, RemeshOptions options, IProgress<double> progress, CancellationToken cancellationToken)
        {
            TpRemeshOptions native = options.ToNative();
            double[] field = options.FlatField();
            double[] guidePoints;
            uint[] guideSizes;
            options.FlatGuides(out guidePoints, out guideSizes);
            var bridge = new ProgressBridge(progress, cancellationToken);
            bridge.ThrowIfCancelled();
            using (var pins = new Pins())
            {
                pins.Remesh(ref native, field, guidePoints, guideSizes);
                using (MeshHandle input = surface.CreateHandle())
                {
                    MeshHandle quads;
                    int status = NativeMethods.tp_remesh(input, ref native, bridge.Callback, IntPtr.Zero, out quads);
                    using (quads)
                    {
                        bridge.Finish(status);
                        return PolyMesh.FromHandle(quads);
                    }
                }
            }
        }

        /// <summary>Stage 2: matches the faces of a quad mesh into tiles. A solve stopped by
        /// the time limit succeeds with <see cref="SolveStatus.TimeLimit"/>. The returned
        /// pattern owns native memory: dispose it when done.</summary>
        public static Pattern Match(PolyMesh quads, PatternOptions options = null, IProgress<double> progress = null,
            CancellationToken cancellationToken = default(CancellationToken))
        {
            if (quads == null)
                throw new ArgumentNullException("quads");
            Native.EnsureReady();
            return MatchCore(quads, options ?? new PatternOptions(), progress, cancellationToken);
        }

        [MethodImpl(MethodImplOptions.NoInlining)]
        static Pattern MatchCore(PolyMesh quads, PatternOptions options, IProgress<double> progress, CancellationToken cancellationToken)
        {
            uint[] forced, excluded;
            TpPatternOptions native = options.ToNative(out forced, out excluded);
            int[] zones = options.ZoneCodes();
            var bridge = new ProgressBridge(progress, cancellationToken);
            bridge.ThrowIfCancelled();
            MeshHandle mesh = quads.CreateHandle();
            PatternHandle pattern = null;
            using (var pins = new Pins())
            {
                try
                {
                    pins.Pattern(ref native, forced, excluded, zones);
                    int status = NativeMethods.tp_pattern_solve(mesh, ref native, bridge.Callback, IntPtr.Zero, out pattern);
                    bridge.Finish(status);
                    return new Pattern(quads, mesh, pattern);
                }
                catch
                {
                    if (pattern != null)
                        pattern.Dispose();
                    mesh.Dispose();
                    throw;
                }
            }
        }

        /// <summary>Stage 3: a box per matched pair and a half tile per unpaired quad, on the
        /// mesh the pattern was solved on, moved by the fit stage so that the joints come close
        /// to the mortar joint (<see cref="TileOptions.Fit"/>, default on; what cannot fit is cut,
        /// <see cref="TileKind.FitCut"/>), cut to <paramref name="surface"/>'s boundary (the
        /// input surface the quads were made from; null: the quad mesh's own boundary),
        /// labelled for the cut list and numbered in laying order; and the report.</summary>
        public static Tiling Tiles(Pattern pattern, TileOptions options = null, PolyMesh surface = null)
        {
            return Tiles(pattern, options, surface, null, default(CancellationToken));
        }

        /// <summary>Stage 3 (see <see cref="Tiles(Pattern, TileOptions, PolyMesh)"/>) reporting the
        /// fit stage's progress (the share of its step limit used) to <paramref name="progress"/>
        /// on the calling thread; cancelling <paramref name="cancellationToken"/> stops the fit
        /// soon after and throws <see cref="TilePatternCanceledException"/> (no tiles).</summary>
        public static Tiling Tiles(Pattern pattern, TileOptions options, PolyMesh surface, IProgress<double> progress,
            CancellationToken cancellationToken = default(CancellationToken))
        {
            if (pattern == null)
                throw new ArgumentNullException("pattern");
            Native.EnsureReady();
            return Build(null, pattern, options ?? new TileOptions(), surface, progress, cancellationToken);
        }

        /// <summary>Stage 3 on another copy of the quad mesh (throws
        /// <see cref="InvalidPatternException"/> if the pattern does not fit it).</summary>
        public static Tiling Tiles(PolyMesh quads, Pattern pattern, TileOptions options = null, PolyMesh surface = null)
        {
            return Tiles(quads, pattern, options, surface, null, default(CancellationToken));
        }

        /// <summary>Stage 3 on another copy of the quad mesh, with progress and cancellation (see
        /// <see cref="Tiles(Pattern, TileOptions, PolyMesh, IProgress{double}, CancellationToken)"/>).</summary>
        public static Tiling Tiles(PolyMesh quads, Pattern pattern, TileOptions options, PolyMesh surface, IProgress<double> progress,
            CancellationToken cancellationToken = default(CancellationToken))
        {
            if (quads == null)
                throw new ArgumentNullException("quads");
            if (pattern == null)
                throw new ArgumentNullException("pattern");
            Native.EnsureReady();
            return Build(quads, pattern, options ?? new TileOptions(), surface, progress, cancellationToken);
        }

        /// <summary>Builds the tiles on <paramref name="quads"/> (null: the pattern's own mesh).</summary>
        [MethodImpl(MethodImplOptions.NoInlining)]
        static Tiling Build(PolyMesh quads, Pattern pattern, TileOptions options, PolyMesh surface, IProgress<double> progress,
            CancellationToken cancellationToken)
        {
            TpTileOptions native = options.ToNative();
            var bridge = new ProgressBridge(progress, cancellationToken);
            bridge.ThrowIfCancelled();
            MeshHandle own = quads == null ? null : quads.CreateHandle();
            try
            {
                MeshHandle mesh = own ?? pattern.MeshHandle;
                TilesHandle tiles;
                int status;
                if (surface == null)
                    status = NativeMethods.tp_tiles_build_with_progress_without_surface(mesh, pattern.Handle, IntPtr.Zero, ref native,
                        bridge.Callback, IntPtr.Zero, out tiles);
                else
                    using (MeshHandle boundary = surface.CreateHandle())
                        status = NativeMethods.tp_tiles_build_with_progress(mesh, pattern.Handle, boundary, ref native,
                            bridge.Callback, IntPtr.Zero, out tiles);
                using (tiles)
                {
                    bridge.Finish(status);
                    return ReadTiles(tiles);
                }
            }
            finally
            {
                if (own != null)
                    own.Dispose();
            }
        }

        /// <summary>The whole pipeline in one call, as the command line's <c>run</c>: remeshes
        /// <paramref name="surface"/> (a triangle or polygon mesh), matches the quads and lays,
        /// fits and cuts the tiles to the surface's boundary, on up to six quad meshes
        /// (<see cref="RunOptions.Tries"/>: the strength <see cref="RemeshOptions.Renormalisation"/>,
        /// the smooth field at it, twice and half the strength, the smooth field's quads laid
        /// out for level courses, the smooth field free of the boundary), and keeps the tiles that fit best: first those whose joints
        /// the report does not flag (<see cref="TilingWarningCode.WideJoints"/>), then those whose
        /// cuts it does not flag (<see cref="TilingWarningCode.FitCuts"/>), then the lowest
        /// score (percent of tiles cut + p95 joint deviation per half joint + percent of the
        /// surface uncovered + a quarter of the percent of pieces cut at the edge). The kept tiling's <see cref="Report.Tries"/> lists every try and
        /// <see cref="Report.ChosenTry"/> the one kept (neither when one try was asked for).
        /// <para>Null options are the command line's run's: default tiles, level courses (null
        /// <paramref name="pattern"/>: a <see cref="PatternOptions"/> with
        /// <see cref="Courses.Level"/>) and quads for them
        /// (null <paramref name="remesh"/>: <see cref="RemeshOptions.ForTile(TileOptions, Courses)"/>
        /// of the tile and the pattern's courses). Options given are used as given: remesh for
        /// their courses the same way. The pattern
        /// options' <see cref="PatternOptions.Zones"/> give a bond per face of
        /// <paramref name="surface"/> (each quad takes the zone of the surface face closest to
        /// it), and so do its <see cref="PatternOptions.ExcludedFaces"/> (openings, areas laid
        /// by hand: each quad whose closest surface face is one is neither tiled nor filled,
        /// and its area is left out of the coverage). <see cref="PatternOptions.ForcedPairs"/>
        /// must be empty (<see cref="ArgumentException"/>), since the quads they would name do
        /// not exist yet: call <see cref="Remesh"/>, <see cref="Match"/> and
        /// <see cref="Tiles(Pattern, TileOptions, PolyMesh)"/> one by one for them.</para>
        /// <para><paramref name="progress"/> hears the share of the whole run on the calling
        /// thread, each try an equal share; cancelling <paramref name="cancellationToken"/>
        /// stops the run soon after and throws <see cref="TilePatternCanceledException"/> (no
        /// tiles), in whichever try and stage it comes. Each stage keeps its own time limit,
        /// except that a later try's pattern stage has at most 10 s (the smooth field's try has
        /// the caller's where the first try's quads end rows all over the surface); a later try
        /// whose pattern stage or fit reaches its limit ends the tries, and so does the first try's fit, or
        /// its pattern stage when that limit is 10 s or less (<see cref="TryReport.LimitReached"/>,
        /// <see cref="TryReport.EndedTries"/>). The result owns native
        /// memory (its <see cref="RunResult.Pattern"/>): dispose it when done.</para></summary>
        public static RunResult Run(PolyMesh surface, RemeshOptions remesh = null, PatternOptions pattern = null, TileOptions tiles = null,
            RunOptions run = null, IProgress<double> progress = null, CancellationToken cancellationToken = default(CancellationToken))
        {
            if (surface == null)
                throw new ArgumentNullException("surface");
            Native.EnsureReady();
            // Null options as the command line's run: level courses (free for the bonds that
            // lay tiles both ways) and quads for them and the tile.
            tiles = tiles ?? new TileOptions();
            pattern = pattern ?? new PatternOptions { Courses = Courses.Level };
            remesh = remesh ?? RemeshOptions.ForTile(tiles, pattern.Courses);
            return RunCore(surface, remesh, pattern, tiles, run ?? new RunOptions(), progress, cancellationToken);
        }

        [MethodImpl(MethodImplOptions.NoInlining)]
        static RunResult RunCore(PolyMesh surface, RemeshOptions remesh, PatternOptions pattern, TileOptions tiles, RunOptions run,
            IProgress<double> progress, CancellationToken cancellationToken)
        {
            int forcedCount = pattern.ForcedPairs == null ? 0 : pattern.ForcedPairs.Count;
            if (forcedCount > 0)
                throw new ArgumentException("PatternOptions.ForcedPairs must be empty for Run (it lists " + forcedCount
                    + "): Run makes the quads itself, so no quad can be named before it;"
                    + " call Remesh, Match and Tiles one by one to force pairs (ExcludedFaces, as Zones, name faces of the surface and are taken)", "pattern");
            TpRemeshOptions remeshNative = remesh.ToNative();
            double[] field = remesh.FlatField();
            double[] guidePoints;
            uint[] guideSizes;
            remesh.FlatGuides(out guidePoints, out guideSizes);
            uint[] forced, excluded;
            TpPatternOptions patternNative = pattern.ToNative(out forced, out excluded);
            int[] zones = pattern.ZoneCodes();
            TpTileOptions tileNative = tiles.ToNative();
            TpRunOptions runNative = run.ToNative();
            var bridge = new ProgressBridge(progress, cancellationToken);
            bridge.ThrowIfCancelled();
            MeshHandle quads = null;
            PatternHandle patternHandle = null;
            TilesHandle tilesHandle = null;
            using (var pins = new Pins())
            {
                try
                {
                    pins.Remesh(ref remeshNative, field, guidePoints, guideSizes);
                    pins.Pattern(ref patternNative, forced, excluded, zones);
                    int status;
                    using (MeshHandle input = surface.CreateHandle())
                        status = NativeMethods.tp_run(input, ref remeshNative, ref patternNative, ref tileNative, ref runNative,
                            bridge.Callback, IntPtr.Zero, out quads, out patternHandle, out tilesHandle);
                    bridge.Finish(status);
                    Tiling tiling = ReadTiles(tilesHandle);
                    return new RunResult(new Pattern(PolyMesh.FromHandle(quads), quads, patternHandle), tiling);
                }
                catch
                {
                    if (patternHandle != null)
                        patternHandle.Dispose();
                    if (quads != null)
                        quads.Dispose();
                    throw;
                }
                finally
                {
                    // The tiles are copied out (plain data): the native ones go at once.
                    if (tilesHandle != null)
                        tilesHandle.Dispose();
                }
            }
        }

        /// <summary>Arrays pinned for one native call (the options' pointers point into them),
        /// released together when the call is over.</summary>
        sealed class Pins : IDisposable
        {
            readonly List<GCHandle> handles = new List<GCHandle>();

            /// <summary>Pins <paramref name="array"/> until Dispose; IntPtr.Zero for null.</summary>
            IntPtr Pin(Array array)
            {
                if (array == null)
                    return IntPtr.Zero;
                GCHandle handle = GCHandle.Alloc(array, GCHandleType.Pinned);
                handles.Add(handle);
                return handle.AddrOfPinnedObject();
            }

            /// <summary>The remesh options' field and guide curves (null: none).</summary>
            public void Remesh(ref TpRemeshOptions native, double[] field, double[] guidePoints, uint[] guideSizes)
            {
                if (field != null)
                {
                    native.field_vectors = Pin(field);
                    native.field_count = (UIntPtr)(field.Length / 3);
                }
                if (guideSizes != null)
                {
                    native.guide_points = Pin(guidePoints);
                    native.guide_point_count = (UIntPtr)(guidePoints.Length / 3);
                    native.guide_curve_sizes = Pin(guideSizes);
                    native.guide_count = (UIntPtr)guideSizes.Length;
                }
            }

            /// <summary>The pattern options' forced pairs and excluded faces (NULL when empty;
            /// ToNative set their counts) and zones (null: none).</summary>
            public void Pattern(ref TpPatternOptions native, uint[] forced, uint[] excluded, int[] zones)
            {
                native.forced_pairs = forced.Length == 0 ? IntPtr.Zero : Pin(forced);
                native.excluded_faces = excluded.Length == 0 ? IntPtr.Zero : Pin(excluded);
                if (zones != null)
                {
                    native.zones = Pin(zones);
                    native.zone_count = (UIntPtr)zones.Length;
                }
            }

            public void Dispose()
            {
                foreach (GCHandle handle in handles)
                    if (handle.IsAllocated)
                        handle.Free();
                handles.Clear();
            }
        }

        static Tiling ReadTiles(TilesHandle handle)
        {
            UIntPtr count;
            Native.Check(NativeMethods.tp_tiles_count(handle, out count));
            int n = Native.Count(count);
            var kinds = new int[n];
            var corners = new double[checked(24 * n)];
            var frames = new double[checked(12 * n)];
            var sizes = new double[checked(3 * n)];
            var faces = new uint[checked(2 * n)];
            var steps = new uint[n];
            var kept = new double[n];
            var loopCounts = new uint[n];
            var deviations = new double[n];
            Native.Check(NativeMethods.tp_tiles_copy_kinds(handle, kinds, Native.Size(kinds.Length)));
            Native.Check(NativeMethods.tp_tiles_copy_joint_deviations(handle, deviations, Native.Size(deviations.Length)));
            Native.Check(NativeMethods.tp_tiles_copy_corners(handle, corners, Native.Size(corners.Length)));
            Native.Check(NativeMethods.tp_tiles_copy_frames(handle, frames, Native.Size(frames.Length)));
            Native.Check(NativeMethods.tp_tiles_copy_sizes(handle, sizes, Native.Size(sizes.Length)));
            Native.Check(NativeMethods.tp_tiles_copy_faces(handle, faces, Native.Size(faces.Length)));
            Native.Check(NativeMethods.tp_tiles_copy_steps(handle, steps, Native.Size(steps.Length)));
            Native.Check(NativeMethods.tp_tiles_copy_kept_fractions(handle, kept, Native.Size(kept.Length)));
            Native.Check(NativeMethods.tp_tiles_copy_loop_counts(handle, loopCounts, Native.Size(loopCounts.Length)));
            UIntPtr loopTotal, pointTotal;
            Native.Check(NativeMethods.tp_tiles_outline_counts(handle, out loopTotal, out pointTotal));
            var loopSizes = new uint[Native.Count(loopTotal)];
            var points = new double[checked(2 * Native.Count(pointTotal))];
            Native.Check(NativeMethods.tp_tiles_copy_loop_sizes(handle, loopSizes, Native.Size(loopSizes.Length)));
            Native.Check(NativeMethods.tp_tiles_copy_loop_points(handle, points, Native.Size(points.Length)));
            string[] labels = Text(handle, NativeMethods.tp_tiles_labels).Split(new[] { '\n' }, StringSplitOptions.None);

            var result = new Tile[n];
            int loop = 0, point = 0;
            for (int i = 0; i < n; i++)
            {
                var t = new Tile
                {
                    Index = i,
                    Kind = (TileKind)kinds[i],
                    Corners = Slice(corners, 24 * i, 24),
                    Origin = Slice(frames, 12 * i, 3),
                    XAxis = Slice(frames, 12 * i + 3, 3),
                    YAxis = Slice(frames, 12 * i + 6, 3),
                    ZAxis = Slice(frames, 12 * i + 9, 3),
                    Length = sizes[3 * i],
                    Width = sizes[3 * i + 1],
                    Thickness = sizes[3 * i + 2],
                    Step = checked((int)steps[i]),
                    KeptFraction = kept[i],
                    JointDeviation = deviations[i],
                    Label = i < labels.Length ? labels[i] : "",
                };
                var covered = new List<int>(2);
                for (int k = 0; k < 2; k++)
                    if (faces[2 * i + k] != NativeMethods.TP_NO_FACE)
                        covered.Add(checked((int)faces[2 * i + k]));
                t.Faces = covered.ToArray();
                t.Outline = new double[loopCounts[i]][];
                for (int l = 0; l < t.Outline.Length; l++, loop++)
                {
                    int m = checked((int)loopSizes[loop]);
                    t.Outline[l] = Slice(points, 2 * point, 2 * m);
                    point += m;
                }
                result[i] = t;
            }
            if (loop != loopSizes.Length || 2 * point != points.Length)
                throw new TilePatternException(TilePatternStatus.InvalidArgument, "the outline counts do not add up: " + loop + " loops, " + point + " points read");
            Report report = Report.Parse(Text(handle, NativeMethods.tp_tiles_report_json));
            report.Warnings = Warnings(handle);
            return new Tiling(result, report, Text(handle, NativeMethods.tp_tiles_cutlist_json));
        }

        /// <summary>The warnings through the C ABI: codes and messages, in the report's order.</summary>
        static TilingWarning[] Warnings(TilesHandle handle)
        {
            UIntPtr count;
            Native.Check(NativeMethods.tp_tiles_warning_count(handle, out count));
            var codes = new int[Native.Count(count)];
            Native.Check(NativeMethods.tp_tiles_copy_warning_codes(handle, codes, Native.Size(codes.Length)));
            string[] messages = Text(handle, NativeMethods.tp_tiles_warnings).Split(new[] { '\n' }, StringSplitOptions.None);
            var result = new TilingWarning[codes.Length];
            for (int i = 0; i < codes.Length; i++)
            {
                var code = (TilingWarningCode)codes[i];
                string words = System.Text.RegularExpressions.Regex.Replace(code.ToString(), "(?<=[a-z])([A-Z])", "_$1").ToLowerInvariant();
                result[i] = new TilingWarning { Code = code, Name = words, Message = i < messages.Length ? messages[i] : "" };
            }
            return result;
        }

        internal delegate int TextExport(TilesHandle tiles, byte[] buffer, UIntPtr length, out UIntPtr needed);

        /// <summary>Reads a string export (report, labels, cut list): asks for the size (which
        /// the library answers with TP_BUFFER_TOO_SMALL and the length), then copies.</summary>
        internal static string Text(TilesHandle handle, TextExport export)
        {
            UIntPtr needed;
            int status = export(handle, null, UIntPtr.Zero, out needed);
            if (status != (int)TilePatternStatus.Ok && status != (int)TilePatternStatus.BufferTooSmall)
                Native.Check(status);
            var buffer = new byte[checked(Native.Count(needed) + 1)];
            UIntPtr written;
            Native.Check(export(handle, buffer, Native.Size(buffer.Length), out written));
            return Encoding.UTF8.GetString(buffer, 0, Native.Count(written));
        }

        internal static string ReportJson(TilesHandle handle)
        {
            return Text(handle, NativeMethods.tp_tiles_report_json);
        }

        static double[] Slice(double[] source, int start, int length)
        {
            var result = new double[length];
            Array.Copy(source, start, result, 0, length);
            return result;
        }
    }
}

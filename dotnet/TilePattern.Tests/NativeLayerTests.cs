// The P/Invoke layer against include/tilepattern.h and the loaded library: every export is
// declared, the struct mirrors have the C layout, handles are released exactly once.
using System;
using System.Collections.Generic;
using System.IO;
using System.Linq;
using System.Reflection;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
using System.Text.RegularExpressions;
using NUnit.Framework;

namespace TilePattern.Tests
{
    [TestFixture]
    public class NativeLayerTests
    {
        // ---- the header -------------------------------------------------------------------

        static string header;

        /// <summary>include/tilepattern.h, found from TILEPATTERN_HEADER or above the test assembly.</summary>
        static string Header
        {
            get
            {
                if (header != null)
                    return header;
                string path = Environment.GetEnvironmentVariable("TILEPATTERN_HEADER");
                if (string.IsNullOrEmpty(path))
                {
                    string dir = Path.GetDirectoryName(typeof(NativeLayerTests).Assembly.Location);
                    while (dir != null && !File.Exists(Path.Combine(dir, Path.Combine("include", "tilepattern.h"))))
                        dir = Path.GetDirectoryName(dir);
                    if (dir == null)
                        Assert.Ignore("include/tilepattern.h not found above " + typeof(NativeLayerTests).Assembly.Location);
                    path = Path.Combine(dir, Path.Combine("include", "tilepattern.h"));
                }
                string text = File.ReadAllText(path);
                // Drop comments and the test-only block.
                text = Regex.Replace(text, @"/\*.*?\*/", " ", RegexOptions.Singleline);
                text = Regex.Replace(text, @"//[^\n]*", " ");
                text = Regex.Replace(text, @"#if defined\(TP_TEST_PANIC\).*?#endif", " ", RegexOptions.Singleline);
                return header = text;
            }
        }

        static MethodInfo[] Imports
        {
            get
            {
                return typeof(NativeMethods).GetMethods(BindingFlags.Static | BindingFlags.NonPublic | BindingFlags.Public)
                    .Where(m => (m.Attributes & MethodAttributes.PinvokeImpl) != 0).ToArray();
            }
        }

        [Test]
        public void EveryExportOfTheHeaderIsDeclaredOnce()
        {
            var exports = Regex.Matches(Header, @"\b(tp_\w+)\s*\(").Cast<Match>().Select(m => m.Groups[1].Value).Distinct().ToList();
            Assert.That(exports.Count, Is.GreaterThanOrEqualTo(26));
            var entryPoints = new List<string>();
            foreach (MethodInfo m in Imports)
            {
                var import = (DllImportAttribute)m.GetCustomAttributes(typeof(DllImportAttribute), false).Single();
                Assert.AreEqual("tilepattern", import.Value, m.Name);
                Assert.AreEqual(CallingConvention.Cdecl, import.CallingConvention, m.Name);
                entryPoints.Add(string.IsNullOrEmpty(import.EntryPoint) ? m.Name : import.EntryPoint);
            }
            CollectionAssert.AreEquivalent(exports, entryPoints.Distinct().ToList(), "NativeMethods declares exactly the header's functions");
            var names = Imports.Select(m => m.Name).ToList();
            foreach (string export in exports)
                Assert.AreEqual(1, names.Count(n => n == export), export + " is declared once under its own name");
        }

        [Test]
        public void EveryExportResolvesInTheLoadedLibrary()
        {
            foreach (MethodInfo m in Imports)
                Assert.DoesNotThrow(() => Marshal.Prelink(m), m.Name);
        }

        [Test]
        public void HeaderConstantsMatch()
        {
            var defines = Regex.Matches(Header, @"#define (TP_\w+) (\S+)").Cast<Match>().ToList();
            Assert.That(defines.Count, Is.GreaterThanOrEqualTo(20));
            foreach (Match d in defines)
            {
                FieldInfo field = typeof(NativeMethods).GetField(d.Groups[1].Value, BindingFlags.Static | BindingFlags.NonPublic);
                Assert.IsNotNull(field, d.Groups[1].Value + " is mirrored in NativeMethods");
                long expected = d.Groups[2].Value == "UINT32_MAX" ? uint.MaxValue : long.Parse(d.Groups[2].Value);
                Assert.AreEqual(expected, Convert.ToInt64(field.GetValue(null)), d.Groups[1].Value);
            }
            // The public enums carry the same numbers.
            Assert.AreEqual(NativeMethods.TP_BOND_RUNNING, (int)Bond.RunningBond);
            Assert.AreEqual(NativeMethods.TP_BOND_HERRINGBONE, (int)Bond.Herringbone);
            Assert.AreEqual(NativeMethods.TP_BOND_BASKET_WEAVE, (int)Bond.BasketWeave);
            Assert.AreEqual(NativeMethods.TP_METHOD_MIP, (int)SolveMethod.Mip);
            Assert.AreEqual(NativeMethods.TP_FORMULATION_PAPER, (int)Formulation.Paper);
            Assert.AreEqual(NativeMethods.TP_SOLVE_FEASIBLE, (int)SolveStatus.Feasible);
            Assert.AreEqual(NativeMethods.TP_BOUND_WHOLE_PROGRAM, (int)BoundSource.WholeProgram);
            Assert.AreEqual(NativeMethods.TP_BOUND_LINEAR_RELAXATION, (int)BoundSource.LinearRelaxation);
            Assert.AreEqual(NativeMethods.TP_DIRECTION_ANGLE, (int)FieldDirection.Angle);
            Assert.AreEqual(NativeMethods.TP_DIRECTION_SMOOTH, (int)FieldDirection.Smooth);
            Assert.AreEqual(NativeMethods.TP_TILE_HALF, (int)TileKind.Half);
            Assert.AreEqual(NativeMethods.TP_TILE_FIT_CUT, (int)TileKind.FitCut);
            Assert.AreEqual(NativeMethods.TP_COURSES_FREE, (int)Courses.Free);
            Assert.AreEqual(NativeMethods.TP_COURSES_LEVEL, (int)Courses.Level);
        }

        [Test]
        public void StatusEnumMatchesTheHeader()
        {
            Match body = Regex.Match(Header, @"enum TpStatus[^{]*\{(.*?)\}", RegexOptions.Singleline);
            Assert.IsTrue(body.Success);
            var values = Regex.Matches(body.Groups[1].Value, @"(TP_\w+) = (\d+)").Cast<Match>().ToList();
            Assert.AreEqual(Enum.GetValues(typeof(TilePatternStatus)).Length, values.Count);
            foreach (Match v in values)
            {
                string name = string.Concat(v.Groups[1].Value.Substring(3).Split('_').Select(w => w.Substring(0, 1) + w.Substring(1).ToLowerInvariant()).ToArray());
                Assert.AreEqual(int.Parse(v.Groups[2].Value), (int)Enum.Parse(typeof(TilePatternStatus), name), v.Groups[1].Value);
            }
        }

        // ---- struct layout --------------------------------------------------------------------

        /// <summary>The C layout of a header struct on a 64-bit target: field names (arrays as
        /// name[i]) with offsets, and the size.</summary>
        static KeyValuePair<List<KeyValuePair<string, int>>, int> CLayout(string name)
        {
            Match m = Regex.Match(Header, @"typedef struct " + name + @" \{(.*?)\} " + name + ";", RegexOptions.Singleline);
            Assert.IsTrue(m.Success, name + " in the header");
            var fields = new List<KeyValuePair<string, int>>();
            int offset = 0, align = 1;
            foreach (Match f in Regex.Matches(m.Groups[1].Value, @"([\w\s\*]+?)\s*\b(\w+)(?:\[(\d+)\])?\s*;"))
            {
                string type = f.Groups[1].Value.Trim();
                int size = type.EndsWith("*") ? 8 : type == "double" || type == "size_t" ? 8 : type == "uint32_t" || type == "int32_t" ? 4 : -1;
                Assert.AreNotEqual(-1, size, "C type " + type);
                int count = f.Groups[3].Success ? int.Parse(f.Groups[3].Value) : 1;
                offset = (offset + size - 1) / size * size;
                align = Math.Max(align, size);
                for (int i = 0; i < count; i++)
                    fields.Add(new KeyValuePair<string, int>(count == 1 ? f.Groups[2].Value : f.Groups[2].Value + "[" + i + "]", offset + i * size));
                offset += size * count;
            }
            return new KeyValuePair<List<KeyValuePair<string, int>>, int>(fields, (offset + align - 1) / align * align);
        }

        static void AssertMirror(Type mirror, string cName, Func<string, string> managedName)
        {
            Assert.AreEqual(8, IntPtr.Size, "64-bit targets only");
            var layout = CLayout(cName);
            Assert.AreEqual(layout.Value, Marshal.SizeOf(mirror), cName + " size");
            var managed = mirror.GetFields(BindingFlags.Instance | BindingFlags.Public).Select(f => f.Name).ToList();
            Assert.AreEqual(layout.Key.Count, managed.Count, cName + " field count");
            foreach (var field in layout.Key)
            {
                string n = managedName(field.Key);
                CollectionAssert.Contains(managed, n, cName + "." + field.Key);
                Assert.AreEqual(field.Value, (int)Marshal.OffsetOf(mirror, n), cName + "." + field.Key + " offset");
            }
        }

        [Test]
        public void StructMirrorsHaveTheHeadersLayout()
        {
            Func<string, string> same = n => n;
            Func<string, string> up = n => n.StartsWith("up[") ? "up_" + "xyz"[n[3] - '0'] : n;
            AssertMirror(typeof(TpPatternOptions), "TpPatternOptions", up);
            AssertMirror(typeof(TpPatternSummary), "TpPatternSummary", same);
            AssertMirror(typeof(TpTileOptions), "TpTileOptions", up);
            AssertMirror(typeof(TpRemeshOptions), "TpRemeshOptions", n => n.StartsWith("direction_vector[") ? "direction_" + "xyz"[n[17] - '0'] : n);
            AssertMirror(typeof(TpRunOptions), "TpRunOptions", same);
            Assert.AreEqual(8, Marshal.SizeOf(typeof(TpRunOptions)));
            Assert.AreEqual(120, Marshal.SizeOf(typeof(TpPatternOptions)));
            Assert.AreEqual(96, Marshal.SizeOf(typeof(TpPatternSummary)));
            Assert.AreEqual(152, Marshal.SizeOf(typeof(TpRemeshOptions)));
            // The ABI 5 size ends where the ABI 6 fields begin.
            Assert.AreEqual(96, (int)Marshal.OffsetOf(typeof(TpRemeshOptions), "guide_points"));
            Assert.AreEqual(136, Marshal.SizeOf(typeof(TpTileOptions)));
            // The ABI 2 sizes end where the ABI 3 fields begin.
            Assert.AreEqual(64, (int)Marshal.OffsetOf(typeof(TpPatternOptions), "courses"));
            // The ABI 3 size ends where the ABI 4 field begins.
            Assert.AreEqual(96, (int)Marshal.OffsetOf(typeof(TpPatternOptions), "gap"));
            // The ABI 5 size ends where the ABI 6 fields (zones) begin.
            Assert.AreEqual(104, (int)Marshal.OffsetOf(typeof(TpPatternOptions), "zones"));
            Assert.AreEqual(88, (int)Marshal.OffsetOf(typeof(TpTileOptions), "fit"));
            // The ABI 6 sizes end where the ABI 7 fields (creases) begin.
            Assert.AreEqual(136, (int)Marshal.OffsetOf(typeof(TpRemeshOptions), "creases"));
            Assert.AreEqual(128, (int)Marshal.OffsetOf(typeof(TpTileOptions), "creases"));
            // The ABI 7 size ends where the ABI 8 field (renormalisation) begins.
            Assert.AreEqual(144, (int)Marshal.OffsetOf(typeof(TpRemeshOptions), "renormalisation"));
        }

        static void AssertLibrarySize(string name, uint library, Type mirror)
        {
            int wrapper = Marshal.SizeOf(mirror);
            if (library > wrapper)
                Assert.Ignore(name + ": the loaded library's struct_size is " + library + ", the header's (and this wrapper's) " + wrapper
                    + ": the library is newer than include/tilepattern.h. Safe (struct_size versioning, 512-byte return buffers), but regenerate the header and update the mirrors.");
            Assert.AreEqual(wrapper, (int)library, name + ".struct_size from the library");
        }

        [Test]
        public void PatternOptionsStructSizeEqualsTheLibrarys()
        {
            AssertLibrarySize("TpPatternOptions", NativeMethods.tp_pattern_options_default().value.struct_size, typeof(TpPatternOptions));
        }

        [Test]
        public void RemeshOptionsStructSizeEqualsTheLibrarys()
        {
            AssertLibrarySize("TpRemeshOptions", NativeMethods.tp_remesh_options_default().value.struct_size, typeof(TpRemeshOptions));
        }

        [Test]
        public void TileOptionsStructSizeEqualsTheLibrarys()
        {
            AssertLibrarySize("TpTileOptions", NativeMethods.tp_tile_options_default().value.struct_size, typeof(TpTileOptions));
        }

        [Test]
        public void RunOptionsStructSizeEqualsTheLibrarys()
        {
            // Returned by value in a register (8 bytes), read back whole.
            TpRunOptions d = NativeMethods.tp_run_options_default();
            AssertLibrarySize("TpRunOptions", d.struct_size, typeof(TpRunOptions));
            Assert.AreEqual(0u, d.tries, "automatic by default");
            Assert.AreEqual(0, new RunOptions().Tries);
        }

        [Test]
        public void OptionsAreSentWithTheWrappersStructSize()
        {
            uint[] forced, excluded;
            Assert.AreEqual((uint)Marshal.SizeOf(typeof(TpPatternOptions)), new PatternOptions().ToNative(out forced, out excluded).struct_size);
            Assert.AreEqual((uint)Marshal.SizeOf(typeof(TpRemeshOptions)), new RemeshOptions().ToNative().struct_size);
            Assert.AreEqual((uint)Marshal.SizeOf(typeof(TpTileOptions)), new TileOptions().ToNative().struct_size);
            Assert.AreEqual((uint)Marshal.SizeOf(typeof(TpRunOptions)), new RunOptions { Tries = 2 }.ToNative().struct_size);
            Assert.AreEqual(2u, new RunOptions { Tries = 2 }.ToNative().tries);
        }

        [DllImport("tilepattern", CallingConvention = CallingConvention.Cdecl, EntryPoint = "tp_pattern_summary")]
        static extern int tp_pattern_summary_raw(PatternHandle pattern, IntPtr output);

        [MethodImpl(MethodImplOptions.NoInlining)]
        static int SummaryRaw(PatternHandle pattern, IntPtr output)
        {
            return tp_pattern_summary_raw(pattern, output);
        }

        [Test]
        public void SummaryWritesExactlyTheMirrorsBytes()
        {
            int size = Marshal.SizeOf(typeof(TpPatternSummary));
            IntPtr buffer = Marshal.AllocHGlobal(size + 64);
            try
            {
                for (int i = 0; i < size + 64; i++)
                    Marshal.WriteByte(buffer, i, 0xCD);
                using (Pattern pattern = TilePatternEngine.Match(TestMeshes.Grid(10, 10), new PatternOptions { Weight = 2.0 }))
                {
                    Assert.AreEqual(0, SummaryRaw(pattern.Handle, buffer));
                    for (int i = size; i < size + 64; i++)
                        Assert.AreEqual(0xCD, Marshal.ReadByte(buffer, i), "byte " + i + " past the struct is untouched");
                    var raw = (TpPatternSummary)Marshal.PtrToStructure(buffer, typeof(TpPatternSummary));
                    Assert.AreEqual(100UL, raw.faces.ToUInt64());
                    Assert.AreEqual(49UL, raw.pairs.ToUInt64());
                    Assert.AreEqual(2UL, raw.unpaired.ToUInt64());
                    Assert.AreEqual(49.0, raw.objective);
                    Assert.AreEqual(49.0, raw.bound);
                    Assert.AreEqual(NativeMethods.TP_SOLVE_OPTIMAL, raw.status);
                    Assert.AreEqual(pattern.Seconds, raw.seconds);
                }
            }
            finally
            {
                Marshal.FreeHGlobal(buffer);
            }
        }

        // ---- handles ----------------------------------------------------------------------------

        [Test]
        public void DisposeTwiceIsSafe()
        {
            Pattern pattern = TilePatternEngine.Match(TestMeshes.Grid(4, 4));
            pattern.Dispose();
            pattern.Dispose();
            Assert.IsTrue(pattern.IsDisposed);
            Assert.IsNotEmpty(pattern.Pairs, "the data stays readable");
            Assert.Throws<ObjectDisposedException>(() => TilePatternEngine.Tiles(pattern));

            MeshHandle mesh = TestMeshes.Grid(2, 2).CreateHandle();
            mesh.Dispose();
            mesh.Dispose();
            Assert.IsTrue(mesh.IsClosed);
            UIntPtr a, b, c;
            Assert.Throws<ObjectDisposedException>(() => NativeMethods.tp_mesh_counts(mesh, out a, out b, out c));

            new MeshHandle().Dispose(); // never held a pointer: nothing to free
        }

        [MethodImpl(MethodImplOptions.NoInlining)]
        static List<WeakReference> Abandon(int count)
        {
            var refs = new List<WeakReference>();
            PolyMesh grid = TestMeshes.Grid(6, 6);
            for (int i = 0; i < count; i++)
            {
                MeshHandle mesh = grid.CreateHandle();
                refs.Add(new WeakReference(mesh));
                Pattern pattern = TilePatternEngine.Match(grid, new PatternOptions { TimeLimitSeconds = 0 });
                refs.Add(new WeakReference(pattern));
            }
            return refs;
        }

        [Test]
        public void ForgottenHandlesAreReleasedByTheFinalizer()
        {
            List<WeakReference> refs = Abandon(300);
            for (int i = 0; i < 3 && refs.Any(r => r.IsAlive); i++)
            {
                GC.Collect();
                GC.WaitForPendingFinalizers();
                GC.Collect();
            }
            Assert.IsFalse(refs.Any(r => r.IsAlive), "every abandoned handle was collected");
            // The library still works after the finalizer thread freed 600 handles.
            using (Pattern p = TilePatternEngine.Match(TestMeshes.Grid(4, 4)))
                Assert.IsNotEmpty(p.Pairs);
        }

        [Test]
        public void ReleaseRunsOnceForAFinalizedHandle()
        {
            // A long weak reference still sees the handle after its finalizer ran.
            var weak = MakeAbandonedHandle();
            GC.Collect();
            GC.WaitForPendingFinalizers();
            var handle = weak.Target as MeshHandle;
            if (handle == null)
                Assert.Ignore("the runtime reclaimed the handle before it could be inspected");
            Assert.IsTrue(handle.IsClosed, "the finalizer released it");
            handle.Dispose(); // and a Dispose afterwards does nothing
        }

        [MethodImpl(MethodImplOptions.NoInlining)]
        static WeakReference MakeAbandonedHandle()
        {
            return new WeakReference(TestMeshes.Grid(2, 2).CreateHandle(), true);
        }
    }
}

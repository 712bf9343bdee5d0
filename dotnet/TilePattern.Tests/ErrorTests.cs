// Every TpStatus that can be provoked maps to its exception, with the library's message.
using System;
using System.Collections.Generic;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
using NUnit.Framework;

namespace TilePattern.Tests
{
    [TestFixture]
    public class ErrorTests
    {
        static readonly double[] Square = { 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0 };

        static T Fails<T>(TestDelegate call, string messagePart) where T : Exception, ITilePatternError
        {
            var e = Assert.Throws<T>(call);
            StringAssert.Contains(messagePart, e.NativeMessage);
            StringAssert.Contains(messagePart, e.Message);
            return e;
        }

        // ---- managed argument checks, before the library is called ----------------------

        [Test]
        public void NullArgumentsAreArgumentNullExceptions()
        {
            Assert.Throws<ArgumentNullException>(() => TilePatternEngine.Remesh(null));
            Assert.Throws<ArgumentNullException>(() => TilePatternEngine.Match(null));
            Assert.Throws<ArgumentNullException>(() => TilePatternEngine.Tiles(null));
            Assert.Throws<ArgumentNullException>(() => TilePatternEngine.Tiles(null, null));
            Assert.Throws<ArgumentNullException>(() => TilePatternEngine.Validate(null));
            Assert.Throws<ArgumentNullException>(() => new PolyMesh(null, new int[0], new int[0]));
            Assert.Throws<ArgumentNullException>(() => PolyMesh.FromFaces(Square, null));
            Assert.Throws<ArgumentNullException>(() => RemeshOptions.ForTile(null));
        }

        [Test]
        public void InconsistentArraysAreArgumentExceptions()
        {
            Assert.Throws<ArgumentException>(() => new PolyMesh(new double[] { 0, 0 }, new int[0], new int[0]));
            Assert.Throws<ArgumentException>(() => new PolyMesh(Square, new[] { 0, 1, 2, 3 }, new[] { 3 }));
            Assert.Throws<ArgumentOutOfRangeException>(() => new PolyMesh(Square, new[] { 0, 1, -2 }, new[] { 3 }));
            Assert.Throws<ArgumentOutOfRangeException>(() => new PolyMesh(Square, new[] { 0, 1, 2 }, new[] { -3 }));
            var options = new PatternOptions();
            options.ExcludedFaces.Add(-1);
            Assert.Throws<ArgumentOutOfRangeException>(() => TilePatternEngine.Match(TestMeshes.Grid(2, 2), options));
            Assert.Throws<ArgumentException>(() => TilePatternEngine.Remesh(TestMeshes.Grid(2, 2), new RemeshOptions { DirectionVector = new[] { 1.0 } }));
        }

        // ---- TP_INVALID_MESH ----------------------------------------------------------------

        [Test]
        public void NaNCoordinateIsAnInvalidMesh()
        {
            var v = (double[])Square.Clone();
            v[3 * 2 + 1] = double.NaN;
            Fails<InvalidMeshException>(() => TilePatternEngine.Validate(new PolyMesh(v, new[] { 0, 1, 2, 3 }, new[] { 4 })), "vertex 2");
            v[3 * 2 + 1] = double.PositiveInfinity;
            Assert.Throws<InvalidMeshException>(() => TilePatternEngine.Match(new PolyMesh(v, new[] { 0, 1, 2, 3 }, new[] { 4 })));
        }

        [Test]
        public void IndexOutOfRangeIsAnInvalidMesh()
        {
            var e = Fails<InvalidMeshException>(() => TilePatternEngine.Validate(new PolyMesh(Square, new[] { 0, 1, 2, 0, 2, 9 }, new[] { 3, 3 })), "face 1");
            Assert.AreEqual(TilePatternStatus.InvalidMesh, e.Status);
            Assert.IsInstanceOf<TilePatternException>(e);
        }

        [Test]
        public void EmptyMeshIsAnInvalidMesh()
        {
            Fails<InvalidMeshException>(() => TilePatternEngine.Validate(new PolyMesh(new double[0], new int[0], new int[0])), "empty");
            Assert.Throws<InvalidMeshException>(() => TilePatternEngine.Remesh(new PolyMesh(new double[0], new int[0], new int[0])));
        }

        [Test]
        public void BadFacesAreInvalidMeshes()
        {
            Fails<InvalidMeshException>(() => TilePatternEngine.Validate(new PolyMesh(Square, new[] { 0, 1, 1, 3 }, new[] { 4 })), "more than once");
            Fails<InvalidMeshException>(() => TilePatternEngine.Validate(new PolyMesh(Square, new[] { 0, 1 }, new[] { 2 })), "at least 3");
            // Three triangles on one edge.
            double[] v = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1 };
            Fails<InvalidMeshException>(() => TilePatternEngine.Validate(new PolyMesh(v, new[] { 0, 1, 2, 1, 0, 3, 0, 1, 4 }, new[] { 3, 3, 3 })), "shared by 3");
        }

        // ---- TP_INVALID_ARGUMENT --------------------------------------------------------------

        [Test]
        public void BadPatternOptionsAreInvalidArguments()
        {
            PolyMesh grid = TestMeshes.Grid(4, 4);
            Fails<InvalidArgumentException>(() => TilePatternEngine.Match(grid, new PatternOptions { Bond = (Bond)7 }), "bond 7");
            Fails<InvalidArgumentException>(() => TilePatternEngine.Match(grid, new PatternOptions { Method = (SolveMethod)5 }), "method 5");
            Fails<InvalidArgumentException>(() => TilePatternEngine.Match(grid, new PatternOptions { Formulation = (Formulation)3 }), "formulation 3");
            Assert.Throws<InvalidArgumentException>(() => TilePatternEngine.Match(grid, new PatternOptions { Weight = double.NaN }));
            Fails<InvalidArgumentException>(() => TilePatternEngine.Match(grid, new PatternOptions { TimeLimitSeconds = -1 }), "time limit");
            Fails<InvalidArgumentException>(() => TilePatternEngine.Match(grid, new PatternOptions { Gap = 1.5 }), "relative gap");
            Fails<InvalidArgumentException>(() => TilePatternEngine.Match(grid, new PatternOptions { Gap = double.NaN }), "relative gap");
            var far = new PatternOptions();
            far.ForcedPairs.Add(new FacePair(0, 15));
            Fails<InvalidArgumentException>(() => TilePatternEngine.Match(grid, far), "[0, 15]");
            var outside = new PatternOptions();
            outside.ExcludedFaces.Add(16);
            Fails<InvalidArgumentException>(() => TilePatternEngine.Match(grid, outside), "face 16");
        }

        [Test]
        public void BadTileOptionsAreInvalidArguments()
        {
            using (Pattern pattern = TilePatternEngine.Match(TestMeshes.Grid(4, 4)))
            {
                Fails<InvalidArgumentException>(() => TilePatternEngine.Tiles(pattern, new TileOptions { Length = 0 }), "length");
                Assert.Throws<InvalidArgumentException>(() => TilePatternEngine.Tiles(pattern, new TileOptions { Width = double.NaN }));
            }
        }

        [Test]
        public void BadRemeshOptionsAreInvalidArguments()
        {
            PolyMesh surface = TestMeshes.CurvedTriangles(6, 1.0, 0.1);
            Assert.Throws<InvalidArgumentException>(() => TilePatternEngine.Remesh(surface, new RemeshOptions { TargetEdge = 0 }));
            Fails<InvalidArgumentException>(() => TilePatternEngine.Remesh(surface, new RemeshOptions { Direction = (FieldDirection)9 }), "direction 9");
        }

        [Test]
        public void NativeChecksOfStructSizeAndCounts()
        {
            // Paths the public API never takes: checked at the C boundary.
            TpTileOptions tile = NativeMethods.tp_tile_options_default().value;
            tile.struct_size = 0;
            using (Pattern pattern = TilePatternEngine.Match(TestMeshes.Grid(2, 2)))
            {
                TilesHandle tiles;
                int status = NativeMethods.tp_tiles_build(pattern.MeshHandle, pattern.Handle, ref tile, out tiles);
                tiles.Dispose();
                Assert.AreEqual((int)TilePatternStatus.InvalidArgument, status);
                Fails<InvalidArgumentException>(() => Native.Check(status), "struct_size");
            }
            MeshHandle mesh;
            int s = NativeMethods.tp_mesh_new(Square, (UIntPtr)4, new uint[] { 0, 1, 2, 3 }, (UIntPtr)3, new uint[] { 4 }, (UIntPtr)1, out mesh);
            mesh.Dispose();
            Assert.AreEqual((int)TilePatternStatus.InvalidArgument, s);
            Fails<InvalidArgumentException>(() => Native.Check(s), "index_count");
        }

        // ---- TP_INVALID_PATTERN ---------------------------------------------------------------

        [Test]
        public void PatternOnAnotherMeshIsAnInvalidPattern()
        {
            using (Pattern pattern = TilePatternEngine.Match(TestMeshes.Grid(10, 10)))
            {
                var e = Assert.Throws<InvalidPatternException>(() => TilePatternEngine.Tiles(TestMeshes.Grid(3, 3), pattern));
                Assert.AreEqual(TilePatternStatus.InvalidPattern, e.Status);
                Assert.IsNotEmpty(e.NativeMessage);
            }
        }

        // ---- TP_NULL_POINTER -------------------------------------------------------------------

        [Test]
        public void NullHandlesAreNullPointers()
        {
            UIntPtr a, b, c;
            using (var empty = new MeshHandle())
            {
                int status = NativeMethods.tp_mesh_counts(empty, out a, out b, out c);
                Assert.AreEqual((int)TilePatternStatus.NullPointer, status);
                Fails<NullPointerException>(() => Native.Check(status), "mesh is NULL");
            }
            using (var empty = new PatternHandle())
            {
                TpPatternSummary summary;
                Assert.AreEqual((int)TilePatternStatus.NullPointer, NativeMethods.tp_pattern_summary(empty, out summary));
            }
            using (var empty = new TilesHandle())
            {
                UIntPtr n;
                Assert.AreEqual((int)TilePatternStatus.NullPointer, NativeMethods.tp_tiles_count(empty, out n));
            }
        }

        [Test]
        public void NullBufferIsANullPointer()
        {
            using (Pattern pattern = TilePatternEngine.Match(TestMeshes.Grid(2, 2)))
            {
                int status = NativeMethods.tp_pattern_copy_pairs(pattern.Handle, null, (UIntPtr)4);
                Fails<NullPointerException>(() => Native.Check(status), "out is NULL");
            }
        }

        // ---- TP_BUFFER_TOO_SMALL ------------------------------------------------------------------

        [Test]
        public void ShortBuffersAreBufferTooSmall()
        {
            using (MeshHandle mesh = TestMeshes.Grid(3, 2).CreateHandle())
            {
                int status = NativeMethods.tp_mesh_copy_vertices(mesh, new double[35], (UIntPtr)35);
                Fails<BufferTooSmallException>(() => Native.Check(status), "35");
                Assert.AreEqual((int)TilePatternStatus.BufferTooSmall,
                    NativeMethods.tp_mesh_copy_faces(mesh, new uint[24], (UIntPtr)24, new uint[5], (UIntPtr)5));
            }
            using (Pattern pattern = TilePatternEngine.Match(TestMeshes.Grid(4, 4)))
            using (MeshHandle mesh = pattern.QuadMesh.CreateHandle())
            {
                var tile = new TileOptions { Length = 1.9, Width = 0.95, Thickness = 0.1, Joint = 0.1 }.ToNative();
                TilesHandle tiles;
                Native.Check(NativeMethods.tp_tiles_build(mesh, pattern.Handle, ref tile, out tiles));
                using (tiles)
                {
                    UIntPtr needed;
                    Assert.AreEqual((int)TilePatternStatus.BufferTooSmall, NativeMethods.tp_tiles_report_json(tiles, null, UIntPtr.Zero, out needed));
                    Assert.Greater(needed.ToUInt64(), 100UL);
                    var small = new byte[10];
                    UIntPtr again;
                    Assert.AreEqual((int)TilePatternStatus.BufferTooSmall, NativeMethods.tp_tiles_report_json(tiles, small, (UIntPtr)10, out again));
                    Assert.AreEqual(needed, again);
                    Assert.AreEqual(new byte[10], small, "nothing written on failure");
                    StringAssert.StartsWith("{", TilePatternEngine.ReportJson(tiles));
                    UIntPtr count;
                    Native.Check(NativeMethods.tp_tiles_count(tiles, out count));
                    int n = (int)count.ToUInt64();
                    Assert.AreEqual((int)TilePatternStatus.BufferTooSmall, NativeMethods.tp_tiles_copy_corners(tiles, new double[24 * n - 1], (UIntPtr)(24 * n - 1)));
                }
            }
        }

        // ---- codes that cannot be provoked through this ABI: the mapping itself ---------------------

        [Test]
        public void EveryStatusMapsToItsException()
        {
            var expected = new Dictionary<TilePatternStatus, Type>
            {
                { TilePatternStatus.NullPointer, typeof(NullPointerException) },
                { TilePatternStatus.InvalidArgument, typeof(InvalidArgumentException) },
                { TilePatternStatus.BufferTooSmall, typeof(BufferTooSmallException) },
                { TilePatternStatus.InvalidMesh, typeof(InvalidMeshException) },
                { TilePatternStatus.InvalidPattern, typeof(InvalidPatternException) },
                { TilePatternStatus.SolverFailed, typeof(SolverFailedException) },
                { TilePatternStatus.TimeLimit, typeof(SolverTimeLimitException) },
                { TilePatternStatus.Cancelled, typeof(TilePatternCanceledException) },
                { TilePatternStatus.NotAvailable, typeof(NotAvailableException) },
                { TilePatternStatus.Panic, typeof(NativePanicException) },
            };
            Assert.AreEqual(10, expected.Count);
            foreach (var pair in expected)
            {
                Exception e = Native.ToException((int)pair.Key, "why", System.Threading.CancellationToken.None);
                Assert.AreEqual(pair.Value, e.GetType(), pair.Key.ToString());
                var error = (ITilePatternError)e;
                Assert.AreEqual(pair.Key, error.Status);
                Assert.AreEqual("why", error.NativeMessage);
                StringAssert.Contains("why", e.Message);
                if (pair.Key == TilePatternStatus.Cancelled)
                    Assert.IsInstanceOf<OperationCanceledException>(e);
                else
                    Assert.IsInstanceOf<TilePatternException>(e);
            }
            // A status newer than the wrapper is still an error, with its number.
            var unknown = (TilePatternException)Native.ToException(42, "new", System.Threading.CancellationToken.None);
            Assert.AreEqual(42, (int)unknown.Status);
            Assert.DoesNotThrow(() => Native.Check(0));
        }

        [Test]
        public void LastErrorIsEmptyAfterSuccessAndPerThread()
        {
            Assert.Throws<InvalidMeshException>(() => TilePatternEngine.Validate(new PolyMesh(new double[0], new int[0], new int[0])));
            StringAssert.Contains("empty", Native.LastErrorMessage());
            string other = null;
            var thread = new System.Threading.Thread(() => other = Native.LastErrorMessage());
            thread.Start();
            thread.Join();
            Assert.AreEqual("", other, "the message is thread-local");
            TilePatternEngine.Validate(TestMeshes.Grid(1, 1));
            Assert.AreEqual("", Native.LastErrorMessage());
        }

        // ---- TP_PANIC: only in a library built with the test-panic feature ---------------------------

        [DllImport("tilepattern", CallingConvention = CallingConvention.Cdecl)]
        static extern int tp_test_panic();

        [MethodImpl(MethodImplOptions.NoInlining)]
        static int CallTestPanic()
        {
            return tp_test_panic();
        }

        [Test]
        public void PanicIsANativePanicException()
        {
            int status;
            try
            {
                status = CallTestPanic();
            }
            catch (EntryPointNotFoundException)
            {
                Assert.Ignore("tp_test_panic is not exported: the library was built without --features test-panic (make dotnet-test builds without it)");
                return;
            }
            Assert.AreEqual((int)TilePatternStatus.Panic, status);
            Fails<NativePanicException>(() => Native.Check(status), "tp_test_panic was called");
            TilePatternEngine.Validate(TestMeshes.Grid(2, 2));
        }
    }
}

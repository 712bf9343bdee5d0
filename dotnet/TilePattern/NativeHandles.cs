// SafeHandles for the three opaque handle types. The runtime releases a forgotten handle from
// its critical finalizer, and never while a P/Invoke that received it is still running
// (the marshaller holds a reference count for the duration of the call).
using System;
using System.Runtime.InteropServices;

namespace TilePattern
{
    /// <summary>Tells the garbage collector about native memory that a handle keeps alive, so
    /// that a host that drops patterns without disposing them (Grasshopper re-solving) gets
    /// them finalized in time; the pressure is removed when the handle is released, by Dispose
    /// or by its finalizer.</summary>
    internal static class NativePressure
    {
        static long outstanding;

        /// <summary>Bytes currently announced (for tests).</summary>
        internal static long Outstanding { get { return System.Threading.Interlocked.Read(ref outstanding); } }

        internal static void Add(long bytes)
        {
            if (bytes <= 0)
                return;
            GC.AddMemoryPressure(bytes);
            System.Threading.Interlocked.Add(ref outstanding, bytes);
        }

        internal static void Remove(long bytes)
        {
            if (bytes <= 0)
                return;
            GC.RemoveMemoryPressure(bytes);
            System.Threading.Interlocked.Add(ref outstanding, -bytes);
        }
    }

    /// <summary>Owns a TpMesh*; released with tp_mesh_free.</summary>
    internal sealed class MeshHandle : SafeHandle
    {
        public MeshHandle() : base(IntPtr.Zero, true) { }

        public override bool IsInvalid { get { return handle == IntPtr.Zero; } }

        long pressure;

        /// <summary>Announces the native memory this handle holds (once; see NativePressure).</summary>
        internal void AddPressure(long bytes)
        {
            if (IsInvalid || System.Threading.Interlocked.CompareExchange(ref pressure, bytes, 0) != 0)
                return;
            NativePressure.Add(bytes);
        }

        protected override bool ReleaseHandle()
        {
            NativeMethods.tp_mesh_free(handle);
            NativePressure.Remove(System.Threading.Interlocked.Exchange(ref pressure, 0));
            return true;
        }
    }

    /// <summary>Owns a TpPattern*; released with tp_pattern_free.</summary>
    internal sealed class PatternHandle : SafeHandle
    {
        public PatternHandle() : base(IntPtr.Zero, true) { }

        public override bool IsInvalid { get { return handle == IntPtr.Zero; } }

        long pressure;

        /// <summary>Announces the native memory this handle holds (once; see NativePressure).</summary>
        internal void AddPressure(long bytes)
        {
            if (IsInvalid || System.Threading.Interlocked.CompareExchange(ref pressure, bytes, 0) != 0)
                return;
            NativePressure.Add(bytes);
        }

        protected override bool ReleaseHandle()
        {
            NativeMethods.tp_pattern_free(handle);
            NativePressure.Remove(System.Threading.Interlocked.Exchange(ref pressure, 0));
            return true;
        }
    }

    /// <summary>Owns a TpTiles*; released with tp_tiles_free.</summary>
    internal sealed class TilesHandle : SafeHandle
    {
        public TilesHandle() : base(IntPtr.Zero, true) { }

        public override bool IsInvalid { get { return handle == IntPtr.Zero; } }

        protected override bool ReleaseHandle()
        {
            NativeMethods.tp_tiles_free(handle);
            return true;
        }
    }
}

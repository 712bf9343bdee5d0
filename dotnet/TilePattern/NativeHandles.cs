// SafeHandles for the three opaque handle types. The runtime releases a forgotten handle from
// its critical finalizer, and never while a P/Invoke that received it is still running
// (the marshaller holds a reference count for the duration of the call).
using System;
using System.Runtime.InteropServices;

namespace TilePattern
{
    /// <summary>Owns a TpMesh*; released with tp_mesh_free.</summary>
    internal sealed class MeshHandle : SafeHandle
    {
        public MeshHandle() : base(IntPtr.Zero, true) { }

        public override bool IsInvalid { get { return handle == IntPtr.Zero; } }

        protected override bool ReleaseHandle()
        {
            NativeMethods.tp_mesh_free(handle);
            return true;
        }
    }

    /// <summary>Owns a TpPattern*; released with tp_pattern_free.</summary>
    internal sealed class PatternHandle : SafeHandle
    {
        public PatternHandle() : base(IntPtr.Zero, true) { }

        public override bool IsInvalid { get { return handle == IntPtr.Zero; } }

        protected override bool ReleaseHandle()
        {
            NativeMethods.tp_pattern_free(handle);
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

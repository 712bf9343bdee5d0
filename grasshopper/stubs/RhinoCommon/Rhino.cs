// Reference stub of RhinoCommon: exactly the members the TilePattern components use, with the
// real names, namespaces and signatures (checked by scripts/check-gh-stubs.py against the
// published type stubs of RhinoCommon 7 and 8). Compiled into target/gh/RhinoCommon.dll for
// `make gh-compile`; never shipped (Rhino provides the real assembly). Bodies are empty.
using System;

namespace Rhino
{
    public class RhinoDoc
    {
        RhinoDoc() { }
        public static RhinoDoc ActiveDoc { get { throw null; } }
        public double ModelAbsoluteTolerance { get { throw null; } }
    }
}

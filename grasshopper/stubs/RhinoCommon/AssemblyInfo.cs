// The stub's identity: the real assembly's name (the Grasshopper stub and the components
// reference it by that name).
using System.Reflection;

[assembly: AssemblyTitle("RhinoCommon (reference stub for the TilePattern components)")]
[assembly: AssemblyVersion("7.0.0.0")]

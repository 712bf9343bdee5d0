// The stub's identity: the real assembly's name.
using System.Reflection;

[assembly: AssemblyTitle("Grasshopper (reference stub for the TilePattern components)")]
[assembly: AssemblyVersion("7.0.0.0")]

// Attributes written by hand so that the mcs build (scripts/test-dotnet.sh) and the SDK build
// (TilePattern.csproj, GenerateAssemblyInfo off) produce the same assembly identity.
using System.Reflection;
using System.Runtime.CompilerServices;

[assembly: AssemblyTitle("TilePattern")]
[assembly: AssemblyDescription("C# wrapper of the TilePattern C library: quad remeshing, tile matching, tile boxes and their report.")]
[assembly: AssemblyVersion("0.1.0.0")]
[assembly: AssemblyFileVersion("0.1.0.0")]
[assembly: AssemblyInformationalVersion("0.1.0")]
[assembly: InternalsVisibleTo("TilePattern.Tests")]

// The plug-in's identity for Grasshopper, its icons, and where it finds the native library.
using System;
using System.Drawing;
using System.IO;
using System.Reflection;
using Grasshopper.Kernel;

namespace TilePattern.Gh
{
    public class TilePatternInfo : GH_AssemblyInfo
    {
        public override string Name { get { return "TilePattern"; } }

        public override string Description
        {
            get { return "Tile laying patterns for free-form shells that need as little cutting as possible (Du, Van Mele, Block, IASS 2023): quad remeshing, tile matching, tile boxes and their report."; }
        }

        public override Guid Id { get { return new Guid("2c756546-dffd-4925-ac95-9db3ed75ad4c"); } }

        public override Bitmap Icon { get { return Icons.Load("TilePatternPlugin"); } }

        public override string AuthorName { get { return "TilePattern contributors"; } }

        public override string AuthorContact { get { return "https://github.com/ (see the project's README)"; } }

        public override string Version { get { return "0.1.0"; } }
    }

    /// <summary>Runs when Grasshopper loads the plug-in, before any component: tells the
    /// wrapper the .gha's folder, so it finds runtimes/&lt;rid&gt;/native/ there even when
    /// TilePattern.dll itself was loaded from bytes (Grasshopper's COFF loading, where the
    /// assembly has no location). TILEPATTERN_LIB, if set, wins.</summary>
    public class TilePatternPriority : GH_AssemblyPriority
    {
        public override GH_LoadingInstruction PriorityLoad()
        {
            try
            {
                string location = typeof(TilePatternPriority).Assembly.Location;
                if (!string.IsNullOrEmpty(location) && string.IsNullOrEmpty(Environment.GetEnvironmentVariable("TILEPATTERN_LIB")))
                    TilePatternEngine.UseNativeLibrary(Path.GetDirectoryName(location));
            }
            catch (Exception)
            {
                // The wrapper's own search still applies; components report a missing library.
            }
            return GH_LoadingInstruction.Proceed;
        }
    }

    /// <summary>The 24 x 24 icons embedded from Icons/*.png.</summary>
    internal static class Icons
    {
        public static Bitmap Load(string name)
        {
            Stream stream = Assembly.GetExecutingAssembly().GetManifestResourceStream("TilePattern.Gh.Icons." + name + ".png");
            return stream == null ? null : new Bitmap(stream);
        }
    }
}

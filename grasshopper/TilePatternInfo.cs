// The plug-in's identity for Grasshopper and its icons. (Where it finds the native library:
// NativeSetup in ComponentBase.cs, at the first solve, when Grasshopper knows the .gha's path.)
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
            get { return "Tile laying patterns for free-form shells that need as little cutting as possible (Du, Van Mele, Block, IASS 2023): quad remeshing, tile matching, tile boxes and their report, or all three in one step keeping the best of up to three quad meshes."; }
        }

        /// <summary>The plug-in's id; NativeSetup looks the .gha up by it.</summary>
        internal static readonly Guid AssemblyId = new Guid("2c756546-dffd-4925-ac95-9db3ed75ad4c");

        public override Guid Id { get { return AssemblyId; } }

        public override Bitmap Icon { get { return Icons.Load("TilePatternPlugin"); } }

        public override string AuthorName { get { return "TilePattern contributors"; } }

        public override string AuthorContact { get { return "TilePattern contributors (no public address yet: set it with the manifest's url)"; } }

        public override string Version { get { return "0.1.0"; } }
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

// What a CAD host (the Grasshopper components) needs beyond the three stages, kept free of
// Rhino types so that it is tested here: tile defaults in the document's units, data-tree
// paths that never collide between meshes, fingerprints of a solve's inputs, and where the
// plug-in's native library is.
using System;
using System.Collections.Generic;
using System.Globalization;
using System.IO;
using System.Text;

namespace TilePattern
{
    /// <summary>Lengths of the document's unit system, by the names of Rhino's UnitSystem
    /// members (Millimeters, Centimeters, Meters, Inches, Feet, ...).</summary>
    public static class ModelUnits
    {
        static readonly Dictionary<string, double> Millimetres = new Dictionary<string, double>(StringComparer.OrdinalIgnoreCase)
        {
            { "Angstroms", 1e-7 }, { "Nanometers", 1e-6 }, { "Microns", 1e-3 }, { "Millimeters", 1.0 },
            { "Centimeters", 10.0 }, { "Decimeters", 100.0 }, { "Meters", 1000.0 }, { "Dekameters", 1e4 },
            { "Hectometers", 1e5 }, { "Kilometers", 1e6 }, { "Megameters", 1e9 }, { "Gigameters", 1e12 },
            { "Microinches", 25.4e-6 }, { "Mils", 25.4e-3 }, { "Inches", 25.4 }, { "Feet", 304.8 },
            { "Yards", 914.4 }, { "Miles", 1609344.0 }, { "NauticalMiles", 1852000.0 },
            { "PrinterPoints", 25.4 / 72.0 }, { "PrinterPicas", 25.4 / 6.0 },
        };

        /// <summary>Millimetres in one model unit, or NaN when the unit system has no fixed
        /// length (None, CustomUnits, Unset, an unknown name, null).</summary>
        public static double MillimetresPerUnit(string unitSystem)
        {
            double mm;
            return unitSystem != null && Millimetres.TryGetValue(unitSystem.Trim(), out mm) ? mm : double.NaN;
        }

        /// <summary>A length in millimetres expressed in the model's units (millimetres when the
        /// units are unknown).</summary>
        public static double FromMillimetres(double millimetres, string unitSystem)
        {
            double mm = MillimetresPerUnit(unitSystem);
            return double.IsNaN(mm) ? millimetres : millimetres / mm;
        }
    }

    /// <summary>The standard tile (280 x 140 x 15 mm, joint 10 mm) in a document's units: the
    /// defaults of the Grasshopper components.</summary>
    public sealed class TileDefaults
    {
        public const double LengthMillimetres = 280.0;
        public const double WidthMillimetres = 140.0;
        public const double ThicknessMillimetres = 15.0;
        public const double JointMillimetres = 10.0;

        TileDefaults() { }

        /// <summary>The defaults for a document in <paramref name="unitSystem"/> (a Rhino
        /// UnitSystem member name). When it has no fixed length the defaults are millimetres
        /// and <see cref="UnitsKnown"/> is false.</summary>
        public static TileDefaults For(string unitSystem)
        {
            return new TileDefaults
            {
                UnitSystem = unitSystem,
                UnitsKnown = !double.IsNaN(ModelUnits.MillimetresPerUnit(unitSystem)),
                Length = ModelUnits.FromMillimetres(LengthMillimetres, unitSystem),
                Width = ModelUnits.FromMillimetres(WidthMillimetres, unitSystem),
                Thickness = ModelUnits.FromMillimetres(ThicknessMillimetres, unitSystem),
                Joint = ModelUnits.FromMillimetres(JointMillimetres, unitSystem),
                UnitsPerMm = ModelUnits.FromMillimetres(1.0, unitSystem),
            };
        }

        public string UnitSystem { get; private set; }
        public bool UnitsKnown { get; private set; }
        /// <summary>Tile length in model units.</summary>
        public double Length { get; private set; }
        public double Width { get; private set; }
        public double Thickness { get; private set; }
        public double Joint { get; private set; }

        /// <summary>Model units per millimetre (1 when the units have no fixed length): the
        /// fit's <see cref="TileOptions.UnitsPerMm"/>.</summary>
        public double UnitsPerMm { get; private set; }

        /// <summary>The remesh stage's quad edge: (length + joint) / 2.</summary>
        public double QuadEdge { get { return (Length + Joint) / 2.0; } }

        /// <summary>The quad edge for tiles laid with <paramref name="courses"/>: (length + joint)
        /// / 2, or for level courses at least width + joint (see <see cref="TileOptions.QuadEdge"/>).</summary>
        public double QuadEdgeFor(Courses courses)
        {
            return TileOptions.QuadEdgeOf(Length, Width, Joint, courses);
        }

        /// <summary>Tile options of this size, with <see cref="TileOptions.UnitsPerMm"/> for the
        /// document (the other options keep the library's defaults).</summary>
        public TileOptions ToTileOptions()
        {
            return new TileOptions { Length = Length, Width = Width, Thickness = Thickness, Joint = Joint, UnitsPerMm = UnitsPerMm };
        }
    }

    /// <summary>Data-tree paths (Grasshopper's {a;b;c}) as integer arrays.</summary>
    public static class TreePaths
    {
        /// <summary>The branch of item <paramref name="item"/> of the solve that writes to
        /// <paramref name="targetPath"/>, item <paramref name="targetIndex"/>: the target path,
        /// then the target index, then the item. Two solves never share a target (path, index),
        /// so their branches never collide, whether the meshes came in one list (same path,
        /// different index) or in different branches.</summary>
        public static int[] Branch(int[] targetPath, int targetIndex, int item)
        {
            if (targetPath == null)
                throw new ArgumentNullException("targetPath");
            if (targetIndex < 0)
                throw new ArgumentOutOfRangeException("targetIndex", targetIndex, "not negative");
            var path = new int[targetPath.Length + 2];
            Array.Copy(targetPath, path, targetPath.Length);
            path[targetPath.Length] = targetIndex;
            path[targetPath.Length + 1] = item;
            return path;
        }

        /// <summary>One branch per item, 0 to count - 1 (see <see cref="Branch"/>).</summary>
        public static int[][] Branches(int[] targetPath, int targetIndex, int count)
        {
            var result = new int[count][];
            for (int i = 0; i < count; i++)
                result[i] = Branch(targetPath, targetIndex, i);
            return result;
        }

        /// <summary>{a;b;c}, as Grasshopper writes paths.</summary>
        public static string Format(int[] path)
        {
            var parts = new string[path.Length];
            for (int i = 0; i < path.Length; i++)
                parts[i] = path[i].ToString(CultureInfo.InvariantCulture);
            return "{" + string.Join(";", parts) + "}";
        }
    }

    /// <summary>A fingerprint of a solve's inputs (meshes, numbers, flags, text), so that a host
    /// can tell whether a running or finished solve still answers its current inputs.</summary>
    public sealed class InputKey
    {
        ulong hash = 14695981039346656037UL;
        long items;

        public InputKey Add(PolyMesh mesh)
        {
            Tag(mesh == null ? 0 : 1);
            if (mesh != null)
            {
                foreach (double v in mesh.Vertices)
                    Mix((ulong)BitConverter.DoubleToInt64Bits(v));
                foreach (int size in mesh.FaceSizes)
                    Tag(size);
                foreach (int i in mesh.FaceIndices)
                    Mix((ulong)i);
            }
            return this;
        }

        public InputKey Add(double value)
        {
            Tag(2);
            Mix((ulong)BitConverter.DoubleToInt64Bits(value));
            return this;
        }

        public InputKey Add(int value)
        {
            Tag(3);
            Mix((ulong)value);
            return this;
        }

        public InputKey Add(bool value)
        {
            Tag(4);
            Mix(value ? 1UL : 0UL);
            return this;
        }

        public InputKey Add(string value)
        {
            Tag(5);
            if (value == null)
                Mix(ulong.MaxValue);
            else
                foreach (char c in value)
                    Mix(c);
            return this;
        }

        public InputKey Add(IEnumerable<int> values)
        {
            Tag(6);
            if (values != null)
                foreach (int v in values)
                    Mix((ulong)v);
            return this;
        }

        /// <summary>Any other object: by reference identity (a Pattern, a Tiling).</summary>
        public InputKey AddIdentity(object value)
        {
            Tag(7);
            Mix(value == null ? 0UL : (ulong)System.Runtime.CompilerServices.RuntimeHelpers.GetHashCode(value));
            return this;
        }

        void Tag(long tag)
        {
            items++;
            Mix((ulong)tag ^ 0x9E3779B97F4A7C15UL);
        }

        void Mix(ulong value)
        {
            for (int b = 0; b < 8; b++)
            {
                hash ^= (value >> (8 * b)) & 0xFF;
                hash *= 1099511628211UL;
            }
        }

        public override string ToString()
        {
            return hash.ToString("x16", CultureInfo.InvariantCulture) + "/" + items.ToString(CultureInfo.InvariantCulture);
        }
    }

    /// <summary>Where a plug-in's native library is.</summary>
    public static class PluginLocation
    {
        /// <summary>The folder to hand to <see cref="TilePatternEngine.UseNativeLibrary"/>: the
        /// folder of the plug-in file as the host reports it (Grasshopper knows the .gha's path
        /// even when it loaded the assembly from bytes, where the assembly's own Location is
        /// empty), else the folder of the assembly's own location; null when neither is known.</summary>
        public static string Folder(string hostReportedFile, string assemblyLocation)
        {
            foreach (string file in new[] { hostReportedFile, assemblyLocation })
            {
                if (string.IsNullOrEmpty(file))
                    continue;
                string folder = Path.GetDirectoryName(file);
                if (!string.IsNullOrEmpty(folder))
                    return folder;
            }
            return null;
        }
    }
}

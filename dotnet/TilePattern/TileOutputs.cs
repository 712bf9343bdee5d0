// The tile stage's result as a host shows it: one slot per tile, in tile order, with its
// geometry (made by the host, e.g. a Rhino Brep), label, frame, laying step and kind all at the
// same index; and the solid pieces of a cut tile (every piece, each outer loop with its holes).
using System;
using System.Collections.Generic;
using System.Globalization;

namespace TilePattern
{
    /// <summary>One solid piece of a cut tile: an outer loop and the holes inside it, as closed
    /// polylines in model coordinates on the tile's bottom face (xyz triples, the first point
    /// repeated once at the end), to be extruded along <see cref="TilePieces.Extrusion"/>.</summary>
    public sealed class TilePiece
    {
        internal TilePiece(double[] outer, List<double[]> holes)
        {
            Outer = outer;
            Holes = holes.ToArray();
        }

        public double[] Outer { get; private set; }
        public double[][] Holes { get; private set; }

        /// <summary>The outer loop, then the holes.</summary>
        public double[][] Loops
        {
            get
            {
                var all = new List<double[]> { Outer };
                all.AddRange(Holes);
                return all.ToArray();
            }
        }
    }

    /// <summary>How a tile becomes solids.</summary>
    public static class TilePieces
    {
        /// <summary>The kept pieces of a cut tile: each counter-clockwise outline loop with the
        /// clockwise loops (holes) inside it; empty for an uncut tile (its box is
        /// <see cref="Tile.Corners"/>). A cut that splits the tile gives several pieces, all of
        /// them. Repeated points (a loop that repeats its first point at the end, two equal
        /// points in a row) are dropped before the closing point is added once. Loops with
        /// fewer than 3 distinct points, and holes outside every outer loop, are left out
        /// and named in <paramref name="problems"/> (may be null).</summary>
        public static TilePiece[] Of(Tile tile, IList<string> problems = null)
        {
            if (tile == null)
                throw new ArgumentNullException("tile");
            var outers = new List<double[]>();
            var holes = new List<double[]>();
            double scale = Math.Max(tile.Length, tile.Width);
            double eps = 1e-9 * (scale > 0 ? scale : 1.0);
            for (int l = 0; l < tile.Outline.Length; l++)
            {
                double[] loop = Clean(tile.Outline[l], eps);
                if (loop.Length < 6)
                {
                    if (problems != null)
                        problems.Add("outline loop " + l + " has fewer than 3 distinct points");
                    continue;
                }
                (SignedArea(loop) >= 0 ? outers : holes).Add(loop);
            }
            var pieceHoles = new List<List<double[]>>();
            foreach (double[] o in outers)
                pieceHoles.Add(new List<double[]>());
            foreach (double[] hole in holes)
            {
                int best = -1;
                double bestArea = double.PositiveInfinity;
                for (int o = 0; o < outers.Count; o++)
                {
                    double area = SignedArea(outers[o]);
                    if (area < bestArea && Inside(hole[0], hole[1], outers[o]))
                    {
                        best = o;
                        bestArea = area;
                    }
                }
                if (best < 0)
                {
                    if (problems != null)
                        problems.Add("a hole lies in no outer loop");
                    continue;
                }
                pieceHoles[best].Add(hole);
            }
            var pieces = new TilePiece[outers.Count];
            for (int o = 0; o < outers.Count; o++)
            {
                var modelHoles = new List<double[]>();
                foreach (double[] hole in pieceHoles[o])
                    modelHoles.Add(ToModel(tile, hole));
                pieces[o] = new TilePiece(ToModel(tile, outers[o]), modelHoles);
            }
            return pieces;
        }

        /// <summary>The extrusion of the tile's bottom face to its top: thickness along the
        /// frame's z axis, xyz.</summary>
        public static double[] Extrusion(Tile tile)
        {
            return new[] { tile.ZAxis[0] * tile.Thickness, tile.ZAxis[1] * tile.Thickness, tile.ZAxis[2] * tile.Thickness };
        }

        /// <summary>The 8 corners of an uncut tile's box, each {x, y, z}.</summary>
        public static double[][] BoxCorners(Tile tile)
        {
            var corners = new double[8][];
            for (int i = 0; i < 8; i++)
                corners[i] = tile.Corner(i);
            return corners;
        }

        static double[] Clean(double[] xy, double eps)
        {
            var kept = new List<double>();
            for (int p = 0; p + 1 < xy.Length; p += 2)
            {
                int n = kept.Count;
                if (n >= 2 && Math.Abs(kept[n - 2] - xy[p]) <= eps && Math.Abs(kept[n - 1] - xy[p + 1]) <= eps)
                    continue;
                kept.Add(xy[p]);
                kept.Add(xy[p + 1]);
            }
            while (kept.Count >= 4 && Math.Abs(kept[0] - kept[kept.Count - 2]) <= eps && Math.Abs(kept[1] - kept[kept.Count - 1]) <= eps)
                kept.RemoveRange(kept.Count - 2, 2);
            return kept.ToArray();
        }

        static double SignedArea(double[] xy)
        {
            double a = 0;
            int n = xy.Length / 2;
            for (int i = 0; i < n; i++)
            {
                int j = (i + 1) % n;
                a += xy[2 * i] * xy[2 * j + 1] - xy[2 * j] * xy[2 * i + 1];
            }
            return a / 2;
        }

        static bool Inside(double x, double y, double[] xy)
        {
            bool inside = false;
            int n = xy.Length / 2;
            for (int i = 0, j = n - 1; i < n; j = i++)
            {
                double xi = xy[2 * i], yi = xy[2 * i + 1], xj = xy[2 * j], yj = xy[2 * j + 1];
                if ((yi > y) != (yj > y) && x < (xj - xi) * (y - yi) / (yj - yi) + xi)
                    inside = !inside;
            }
            return inside;
        }

        /// <summary>A cleaned (x, y) loop in the tile's frame as a closed xyz polyline.</summary>
        static double[] ToModel(Tile tile, double[] xy)
        {
            int n = xy.Length / 2;
            var xyz = new double[3 * (n + 1)];
            for (int p = 0; p <= n; p++)
            {
                int q = p % n;
                for (int d = 0; d < 3; d++)
                    xyz[3 * p + d] = tile.Origin[d] + xy[2 * q] * tile.XAxis[d] + xy[2 * q + 1] * tile.YAxis[d];
            }
            return xyz;
        }
    }

    /// <summary>A tile's frame: origin, length axis x, width axis y (xyz each).</summary>
    public sealed class TileFrame
    {
        internal TileFrame(Tile tile)
        {
            Origin = (double[])tile.Origin.Clone();
            XAxis = (double[])tile.XAxis.Clone();
            YAxis = (double[])tile.YAxis.Clone();
        }

        public double[] Origin { get; private set; }
        public double[] XAxis { get; private set; }
        public double[] YAxis { get; private set; }
    }

    /// <summary>The tiles of a <see cref="Tiling"/> as parallel lists, one slot per tile in
    /// tile order: <see cref="Geometry"/>[i], <see cref="Labels"/>[i], <see cref="Frames"/>[i],
    /// <see cref="Steps"/>[i], <see cref="Kinds"/>[i] and <see cref="Deviations"/>[i] describe the
    /// same tile. A tile whose
    /// geometry could not be made keeps its slot with a null geometry and a warning naming it.</summary>
    public sealed class TileOutputs<T> where T : class
    {
        TileOutputs() { }

        /// <summary>Makes the geometry of every tile with <paramref name="make"/>, which gets the
        /// tile and its cut pieces (empty for an uncut tile) and returns the geometry, or null
        /// (or throws) when it cannot; either way the slot stays, null, with a warning.</summary>
        public static TileOutputs<T> Build(Tiling tiling, Func<Tile, TilePiece[], T> make)
        {
            if (tiling == null)
                throw new ArgumentNullException("tiling");
            if (make == null)
                throw new ArgumentNullException("make");
            var r = new TileOutputs<T>();
            foreach (Tile tile in tiling.Tiles)
            {
                var problems = new List<string>();
                T geometry = null;
                try
                {
                    TilePiece[] pieces = TilePieces.Of(tile, problems);
                    if (tile.Outline.Length > 0 && pieces.Length == 0)
                        problems.Add("its cut outline has no usable loop");
                    else
                    {
                        geometry = make(tile, pieces);
                        if (geometry == null)
                            problems.Add(tile.Outline.Length > 0 ? "its cut outline could not be made into a solid (it is not replaced by the uncut box)" : "its box could not be made");
                    }
                }
                catch (Exception e)
                {
                    geometry = null;
                    problems.Add(e.GetType().Name + ": " + e.Message);
                }
                if (problems.Count > 0)
                    r.warnings.Add(Describe(tile) + ": " + string.Join("; ", problems.ToArray()) + (geometry == null ? " (slot left empty)" : ""));
                r.geometry.Add(geometry);
                r.labels.Add(tile.Label);
                r.frames.Add(new TileFrame(tile));
                r.steps.Add(tile.Step);
                r.kinds.Add(KindName(tile.Kind));
                r.deviations.Add(tile.JointDeviation);
            }
            return r;
        }

        readonly List<T> geometry = new List<T>();
        readonly List<string> labels = new List<string>();
        readonly List<TileFrame> frames = new List<TileFrame>();
        readonly List<int> steps = new List<int>();
        readonly List<string> kinds = new List<string>();
        readonly List<double> deviations = new List<double>();
        readonly List<string> warnings = new List<string>();

        public IList<T> Geometry { get { return geometry.AsReadOnly(); } }
        public IList<string> Labels { get { return labels.AsReadOnly(); } }
        public IList<TileFrame> Frames { get { return frames.AsReadOnly(); } }
        public IList<int> Steps { get { return steps.AsReadOnly(); } }
        /// <summary>"full", "half", "boundary" or "fit_cut".</summary>
        public IList<string> Kinds { get { return kinds.AsReadOnly(); } }
        /// <summary>Each tile's worst joint, |gap - joint| in model units
        /// (<see cref="Tile.JointDeviation"/>): to colour a preview of the joints.</summary>
        public IList<double> Deviations { get { return deviations.AsReadOnly(); } }
        /// <summary>One line per tile with a problem, naming the tile.</summary>
        public IList<string> Warnings { get { return warnings.AsReadOnly(); } }
        public int Count { get { return geometry.Count; } }

        /// <summary>"full", "half", "boundary", "fit_cut" (as the report and cut list name them).</summary>
        public static string KindName(TileKind kind)
        {
            switch (kind)
            {
                case TileKind.Full: return "full";
                case TileKind.Half: return "half";
                case TileKind.Boundary: return "boundary";
                case TileKind.FitCut: return "fit_cut";
                default: return ((int)kind).ToString(CultureInfo.InvariantCulture);
            }
        }

        /// <summary>"tile 12 (B3, faces 4, 5)".</summary>
        public static string Describe(Tile tile)
        {
            var faces = new string[tile.Faces.Length];
            for (int i = 0; i < faces.Length; i++)
                faces[i] = tile.Faces[i].ToString(CultureInfo.InvariantCulture);
            return "tile " + tile.Index.ToString(CultureInfo.InvariantCulture) + " (" + tile.Label
                + (faces.Length == 0 ? "" : (faces.Length == 1 ? ", face " : ", faces ") + string.Join(", ", faces)) + ")";
        }
    }
}

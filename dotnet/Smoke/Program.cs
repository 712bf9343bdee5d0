// A minimal program using the wrapper: loads the native library the way an application would
// (runtimes/<rid>/native/ next to TilePattern.dll, no environment variable) and runs the three
// stages on a small grid. scripts/test-dotnet.sh runs it to check the runtimes layout.
using System;
using TilePattern;

namespace TilePattern.Smoke
{
    public static class Program
    {
        public static int Main()
        {
            // First call: options (their defaults come from the library).
            var options = new PatternOptions { TimeLimitSeconds = 5 };
            Console.WriteLine("TilePattern " + TilePatternEngine.NativeVersion + " loaded from " + (TilePatternEngine.NativeLibraryPath ?? "(default search)"));
            const int n = 6;
            var xyz = new double[3 * (n + 1) * (n + 1)];
            for (int j = 0; j <= n; j++)
                for (int i = 0; i <= n; i++)
                {
                    int v = i + (n + 1) * j;
                    xyz[3 * v] = 0.145 * i;
                    xyz[3 * v + 1] = 0.145 * j;
                }
            var faces = new int[n * n][];
            for (int j = 0; j < n; j++)
                for (int i = 0; i < n; i++)
                {
                    int a = i + (n + 1) * j;
                    faces[i + n * j] = new[] { a, a + 1, a + n + 2, a + n + 1 };
                }
            using (Pattern pattern = TilePatternEngine.Match(PolyMesh.FromFaces(xyz, faces), options))
            {
                Tiling tiling = TilePatternEngine.Tiles(pattern);
                Console.WriteLine(pattern + "; " + tiling.Tiles.Length + " tiles, " + tiling.Report.Joints.Contacts + " contacts");
                return tiling.Tiles.Length > 0 && tiling.Report.Faces == n * n ? 0 : 1;
            }
        }
    }
}

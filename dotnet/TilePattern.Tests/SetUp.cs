// Runs once before any test of the namespace: loads the native library before any test
// method that calls a P/Invoke directly is compiled (Mono binds P/Invokes at compile time).
using NUnit.Framework;

namespace TilePattern.Tests
{
    [SetUpFixture]
    public class LibrarySetUp
    {
        [SetUp]
        public void LoadLibrary()
        {
            Native.EnsureReady();
            System.Console.WriteLine("TilePattern native " + TilePatternEngine.NativeVersion + " (ABI " + TilePatternEngine.NativeAbiVersion + ") from "
                + (TilePatternEngine.NativeLibraryPath ?? "the runtime's default search"));
        }
    }
}

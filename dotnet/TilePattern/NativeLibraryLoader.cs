// Finds the native library before the first P/Invoke and points the runtime at it.
//
// Where it looks, in order (first file that loads wins):
//   1. the file named by the environment variable TILEPATTERN_LIB, or set with
//      TilePatternEngine.UseNativeLibrary(path) before the first call; if it names a folder,
//      <folder>/<file> and then the runtimes layout of 2. under that folder;
//   2. <assembly folder>/runtimes/<rid>/native/<file>, rid = win-x64, win-arm64,
//      osx-arm64, osx-x64, linux-x64, linux-arm64 (the process architecture first);
//   3. <assembly folder>/<file>;
// where <file> is tilepattern.dll, libtilepattern.dylib or libtilepattern.so.
//
// How it points the runtime at the file depends on the runtime:
//   - .NET Core 3+ / .NET 5+ (Rhino 8): NativeLibrary.SetDllImportResolver, by reflection
//     because netstandard2.0 does not have it;
//   - .NET Framework on Windows (Rhino 7): LoadLibraryEx preloads the file; Windows then
//     resolves DllImport("tilepattern") to the module already loaded under that name.
//     SetDllDirectory is not used: it is process-wide and would change other plug-ins' search;
//   - Mono (Rhino 7 for Mac, the tests here): dlopen checks the file loads, then
//     mono_dllmap_insert (Mono's embedding API, the runtime version of a .dll.config dllmap)
//     maps "tilepattern" to it;
//   - anything else: a dlopen preload.
// When: before the first P/Invoke is *bound*. Mono binds a P/Invoke when it JIT-compiles the
// method that calls it, and a failed binding stays failed for that method, so the public API
// calls Native.EnsureReady() (which calls EnsureLoaded) from methods that contain no
// P/Invoke themselves, and does the native calls in [NoInlining] helpers.
// Every step is guarded: if nothing works, the runtime's own search (PATH, LD_LIBRARY_PATH,
// DYLD_LIBRARY_PATH, a dllmap, the assembly folder) still applies. EnsureLoaded never throws;
// what happened is in Description, and is added to DllNotFoundException messages.
using System;
using System.Collections.Generic;
using System.IO;
using System.Reflection;
using System.Runtime.InteropServices;
using System.Text;

namespace TilePattern
{
    internal static class NativeLibraryLoader
    {
        internal const string EnvironmentVariable = "TILEPATTERN_LIB";

        static readonly object Gate = new object();
        static bool attempted;
        static string explicitPath;
        static string loadedPath;
        static IntPtr loadedHandle;
        static readonly StringBuilder log = new StringBuilder();

        /// <summary>The file that was loaded, or null when the runtime's default search is left to find it.</summary>
        internal static string LoadedPath
        {
            get { lock (Gate) { return loadedPath; } }
        }

        /// <summary>What the loader tried, one step per line.</summary>
        internal static string Description
        {
            get { lock (Gate) { return log.ToString(); } }
        }

        /// <summary>Sets the file to load; only has an effect before the first native call.</summary>
        internal static bool SetExplicitPath(string path)
        {
            lock (Gate)
            {
                if (attempted)
                    return false;
                explicitPath = path;
                return true;
            }
        }

        internal static void EnsureLoaded()
        {
            lock (Gate)
            {
                if (attempted)
                    return;
                attempted = true;
                try
                {
                    Load();
                }
                catch (Exception e)
                {
                    // Never let a resolver problem escape a type initializer.
                    Note("loader failed: " + e.GetType().Name + ": " + e.Message);
                }
            }
        }

        static void Note(string line)
        {
            log.AppendLine(line);
        }

        internal static bool IsMono
        {
            get { return Type.GetType("Mono.Runtime") != null; }
        }

        internal static bool IsWindows
        {
            get
            {
                try
                {
                    return RuntimeInformation.IsOSPlatform(OSPlatform.Windows);
                }
                catch (Exception)
                {
                    return Path.DirectorySeparatorChar == '\\';
                }
            }
        }

        internal static bool IsMacOS
        {
            get
            {
                try
                {
                    return RuntimeInformation.IsOSPlatform(OSPlatform.OSX);
                }
                catch (Exception)
                {
                    return Directory.Exists("/System/Library/CoreServices");
                }
            }
        }

        internal static string FileName
        {
            get
            {
                if (IsWindows)
                    return "tilepattern.dll";
                return IsMacOS ? "libtilepattern.dylib" : "libtilepattern.so";
            }
        }

        /// <summary>Runtime identifiers to look under, best match first.</summary>
        internal static string[] RuntimeIdentifiers()
        {
            bool arm64 = false;
            try
            {
                arm64 = RuntimeInformation.ProcessArchitecture == Architecture.Arm64;
            }
            catch (Exception)
            {
            }
            string os = IsWindows ? "win" : IsMacOS ? "osx" : "linux";
            string first = arm64 ? "arm64" : "x64", second = arm64 ? "x64" : "arm64";
            // A universal (lipo) dylib is the same file in both osx folders; the second
            // architecture is still tried because Rosetta reports x64 for an arm64 Mac.
            return new[] { os + "-" + first, os + "-" + second, os };
        }

        /// <summary>Files to try, best first; <paramref name="baseDirectory"/> is the assembly folder.</summary>
        internal static List<string> Candidates(string overridePath, string baseDirectory)
        {
            var result = new List<string>();
            if (!string.IsNullOrEmpty(overridePath))
            {
                if (Directory.Exists(overridePath))
                {
                    // A folder: the file in it, or the runtimes layout under it.
                    result.Add(Path.Combine(overridePath, FileName));
                    AddRuntimesLayout(result, overridePath);
                }
                else
                    result.Add(overridePath);
            }
            if (!string.IsNullOrEmpty(baseDirectory))
            {
                AddRuntimesLayout(result, baseDirectory);
                result.Add(Path.Combine(baseDirectory, FileName));
            }
            return result;
        }

        static void AddRuntimesLayout(List<string> result, string folder)
        {
            foreach (string rid in RuntimeIdentifiers())
                result.Add(Path.Combine(Path.Combine(Path.Combine(Path.Combine(folder, "runtimes"), rid), "native"), FileName));
        }

        internal static string AssemblyDirectory()
        {
            try
            {
                string location = typeof(NativeLibraryLoader).Assembly.Location;
                // Empty when the assembly was loaded from bytes (Grasshopper's COFF loading).
                return string.IsNullOrEmpty(location) ? null : Path.GetDirectoryName(location);
            }
            catch (Exception)
            {
                return null;
            }
        }

        static void Load()
        {
            string overridePath = explicitPath;
            if (string.IsNullOrEmpty(overridePath))
                overridePath = Environment.GetEnvironmentVariable(EnvironmentVariable);
            var candidates = Candidates(overridePath, AssemblyDirectory());
            var existing = new List<string>();
            foreach (string path in candidates)
            {
                if (File.Exists(path))
                    existing.Add(Path.GetFullPath(path));
                else
                    Note("not found: " + path);
            }
            if (existing.Count == 0)
            {
                Note("no candidate file: left to the runtime's default search for '" + NativeMethods.Library + "'");
                return;
            }

            if (!IsMono && TryNetCoreResolver(existing))
                return;
            foreach (string path in existing)
            {
                if (IsWindows ? TryWindowsPreload(path) : IsMono ? TryMonoDllMap(path) : TryDlopen(path) != IntPtr.Zero)
                {
                    loadedPath = path;
                    return;
                }
            }
            Note("no candidate loaded: left to the runtime's default search");
        }

        // ---- .NET Core 3+ / .NET 5+ ---------------------------------------------------------

        static MethodInfo tryLoad;
        static List<string> resolverCandidates;

        static bool TryNetCoreResolver(List<string> existing)
        {
            Assembly core = typeof(object).Assembly;
            Type nativeLibrary = core.GetType("System.Runtime.InteropServices.NativeLibrary");
            Type resolverType = core.GetType("System.Runtime.InteropServices.DllImportResolver");
            if (nativeLibrary == null || resolverType == null)
                return false;
            MethodInfo set = nativeLibrary.GetMethod("SetDllImportResolver", new[] { typeof(Assembly), resolverType });
            tryLoad = nativeLibrary.GetMethod("TryLoad", new[] { typeof(string), typeof(IntPtr).MakeByRefType() });
            if (set == null || tryLoad == null)
                return false;
            resolverCandidates = existing;
            MethodInfo resolve = typeof(NativeLibraryLoader).GetMethod("Resolve", BindingFlags.NonPublic | BindingFlags.Static);
            Delegate resolver = Delegate.CreateDelegate(resolverType, resolve);
            try
            {
                set.Invoke(null, new object[] { typeof(NativeLibraryLoader).Assembly, resolver });
            }
            catch (TargetInvocationException e)
            {
                Note("SetDllImportResolver failed: " + e.InnerException.Message);
                return false;
            }
            Note("NativeLibrary resolver registered for: " + string.Join(", ", existing.ToArray()));
            return true;
        }

        // DllImportResolver: called by .NET Core for every DllImport of this assembly.
        static IntPtr Resolve(string libraryName, Assembly assembly, DllImportSearchPath? searchPath)
        {
            if (libraryName != NativeMethods.Library)
                return IntPtr.Zero;
            lock (Gate)
            {
                if (loadedHandle != IntPtr.Zero)
                    return loadedHandle;
                foreach (string path in resolverCandidates)
                {
                    var args = new object[] { path, IntPtr.Zero };
                    if ((bool)tryLoad.Invoke(null, args))
                    {
                        loadedHandle = (IntPtr)args[1];
                        loadedPath = path;
                        Note("loaded " + path);
                        return loadedHandle;
                    }
                    Note("NativeLibrary.TryLoad failed: " + path);
                }
                return IntPtr.Zero; // the runtime's default search follows
            }
        }

        // ---- Windows (.NET Framework) -------------------------------------------------------

        const uint LOAD_WITH_ALTERED_SEARCH_PATH = 0x00000008;

        [DllImport("kernel32", EntryPoint = "LoadLibraryExW", CharSet = CharSet.Unicode, SetLastError = true)]
        static extern IntPtr LoadLibraryEx(string path, IntPtr file, uint flags);

        static bool TryWindowsPreload(string path)
        {
            // LOAD_WITH_ALTERED_SEARCH_PATH: the library's own dependencies (the CBC DLLs) are
            // looked for next to it first.
            IntPtr handle = LoadLibraryEx(path, IntPtr.Zero, LOAD_WITH_ALTERED_SEARCH_PATH);
            if (handle == IntPtr.Zero)
            {
                Note("LoadLibraryEx failed (error " + Marshal.GetLastWin32Error() + "): " + path);
                return false;
            }
            loadedHandle = handle;
            Note("preloaded " + path);
            return true;
        }

        // ---- Mono ---------------------------------------------------------------------------

        [DllImport("__Internal", EntryPoint = "mono_dllmap_insert", CharSet = CharSet.Ansi)]
        static extern void mono_dllmap_insert(IntPtr assembly, string dll, string func, string tdll, string tfunc);

        static bool TryMonoDllMap(string path)
        {
            if (TryDlopen(path) == IntPtr.Zero)
                return false;
            try
            {
                mono_dllmap_insert(IntPtr.Zero, NativeMethods.Library, null, path, null);
                Note("mono dllmap: " + NativeMethods.Library + " -> " + path);
            }
            catch (Exception e)
            {
                // The dlopen preload stays; on macOS dyld matches it by install name.
                Note("mono_dllmap_insert unavailable (" + e.GetType().Name + "); kept the dlopen preload");
            }
            return true;
        }

        // ---- dlopen (Linux, macOS) ----------------------------------------------------------

        const int RTLD_NOW = 2;

        [DllImport("libdl.so.2", EntryPoint = "dlopen")]
        static extern IntPtr dlopen_libdl(string path, int flags);

        [DllImport("libc.so.6", EntryPoint = "dlopen")]
        static extern IntPtr dlopen_libc(string path, int flags);

        [DllImport("/usr/lib/libSystem.B.dylib", EntryPoint = "dlopen")]
        static extern IntPtr dlopen_system(string path, int flags);

        [DllImport("libdl.so.2", EntryPoint = "dlerror")]
        static extern IntPtr dlerror_libdl();

        [DllImport("libc.so.6", EntryPoint = "dlerror")]
        static extern IntPtr dlerror_libc();

        [DllImport("/usr/lib/libSystem.B.dylib", EntryPoint = "dlerror")]
        static extern IntPtr dlerror_system();

        static IntPtr TryDlopen(string path)
        {
            var attempts = IsMacOS
                ? new Func<IntPtr>[] { () => dlopen_system(path, RTLD_NOW) }
                : new Func<IntPtr>[] { () => dlopen_libdl(path, RTLD_NOW), () => dlopen_libc(path, RTLD_NOW) };
            var errors = IsMacOS
                ? new Func<IntPtr>[] { dlerror_system }
                : new Func<IntPtr>[] { dlerror_libdl, dlerror_libc };
            for (int i = 0; i < attempts.Length; i++)
            {
                IntPtr handle;
                try
                {
                    handle = attempts[i]();
                }
                catch (DllNotFoundException)
                {
                    continue;
                }
                catch (EntryPointNotFoundException)
                {
                    continue;
                }
                if (handle != IntPtr.Zero)
                {
                    loadedHandle = handle;
                    Note("dlopen " + path);
                    return handle;
                }
                string why = "";
                try
                {
                    why = Marshal.PtrToStringAnsi(errors[i]()) ?? "";
                }
                catch (Exception)
                {
                }
                Note("dlopen failed: " + path + " " + why);
                return IntPtr.Zero;
            }
            Note("no dlopen available");
            return IntPtr.Zero;
        }
    }
}

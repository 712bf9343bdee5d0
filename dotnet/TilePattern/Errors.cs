// TpStatus as a .NET enum, one exception type per failure status, and the check that turns a
// status plus tp_last_error_message() into the exception.
using System;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
using System.Text;
using System.Threading;

namespace TilePattern
{
    /// <summary>TpStatus: what a native call did. The numbers are the C library's.</summary>
    public enum TilePatternStatus
    {
        /// <summary>TP_OK: success.</summary>
        Ok = 0,
        /// <summary>TP_NULL_POINTER: a required pointer was NULL.</summary>
        NullPointer = 1,
        /// <summary>TP_INVALID_ARGUMENT: an argument or option is out of range.</summary>
        InvalidArgument = 2,
        /// <summary>TP_BUFFER_TOO_SMALL: a buffer was smaller than the data.</summary>
        BufferTooSmall = 3,
        /// <summary>TP_INVALID_MESH: NaN coordinates, bad indices, non-manifold edges, empty mesh.</summary>
        InvalidMesh = 4,
        /// <summary>TP_INVALID_PATTERN: the pattern does not fit the mesh.</summary>
        InvalidPattern = 5,
        /// <summary>TP_SOLVER_FAILED: the MIP solver failed.</summary>
        SolverFailed = 6,
        /// <summary>TP_TIME_LIMIT: the stage hit its time limit before it had any usable result.</summary>
        TimeLimit = 7,
        /// <summary>TP_CANCELLED: the progress callback asked to stop.</summary>
        Cancelled = 8,
        /// <summary>TP_NOT_AVAILABLE: the stage is not available in this build.</summary>
        NotAvailable = 9,
        /// <summary>TP_PANIC: a bug in the library, caught at the boundary.</summary>
        Panic = 10,
    }

    /// <summary>What every exception from the native library carries, including
    /// <see cref="TilePatternCanceledException"/>, which derives from
    /// <see cref="System.OperationCanceledException"/> instead of <see cref="TilePatternException"/>.</summary>
    public interface ITilePatternError
    {
        /// <summary>The native status.</summary>
        TilePatternStatus Status { get; }

        /// <summary>tp_last_error_message() right after the failed call (may be empty).</summary>
        string NativeMessage { get; }
    }

    /// <summary>Base of the exceptions for a failed native call.</summary>
    public class TilePatternException : Exception, ITilePatternError
    {
        public TilePatternException(TilePatternStatus status, string nativeMessage)
            : base(Describe(status, nativeMessage))
        {
            Status = status;
            NativeMessage = nativeMessage ?? "";
        }

        public TilePatternStatus Status { get; private set; }

        public string NativeMessage { get; private set; }

        internal static string Describe(TilePatternStatus status, string nativeMessage)
        {
            return string.IsNullOrEmpty(nativeMessage) ? "TilePattern: " + status : "TilePattern: " + status + ": " + nativeMessage;
        }
    }

    /// <summary>TP_NULL_POINTER: a handle or buffer was missing (the wrapper checks its own
    /// arguments, so this means a disposed or foreign handle reached the library).</summary>
    public class NullPointerException : TilePatternException
    {
        public NullPointerException(string nativeMessage) : base(TilePatternStatus.NullPointer, nativeMessage) { }
    }

    /// <summary>TP_INVALID_ARGUMENT: an option is out of range (weight, time limit, tile size,
    /// a face index in forced pairs or excluded faces, a bond/method/direction value).</summary>
    public class InvalidArgumentException : TilePatternException
    {
        public InvalidArgumentException(string nativeMessage) : base(TilePatternStatus.InvalidArgument, nativeMessage) { }
    }

    /// <summary>TP_BUFFER_TOO_SMALL: a copy buffer was too small (a wrapper bug if it escapes).</summary>
    public class BufferTooSmallException : TilePatternException
    {
        public BufferTooSmallException(string nativeMessage) : base(TilePatternStatus.BufferTooSmall, nativeMessage) { }
    }

    /// <summary>TP_INVALID_MESH: the mesh was refused; the message names the face or vertex.</summary>
    public class InvalidMeshException : TilePatternException
    {
        public InvalidMeshException(string nativeMessage) : base(TilePatternStatus.InvalidMesh, nativeMessage) { }
    }

    /// <summary>TP_INVALID_PATTERN: the pattern does not fit the mesh it is used with.</summary>
    public class InvalidPatternException : TilePatternException
    {
        public InvalidPatternException(string nativeMessage) : base(TilePatternStatus.InvalidPattern, nativeMessage) { }
    }

    /// <summary>TP_SOLVER_FAILED: the MIP solver (CBC) failed.</summary>
    public class SolverFailedException : TilePatternException
    {
        public SolverFailedException(string nativeMessage) : base(TilePatternStatus.SolverFailed, nativeMessage) { }
    }

    /// <summary>TP_TIME_LIMIT: the time limit expired before any usable result. (A solve that
    /// has a pattern when the limit strikes succeeds with <see cref="SolveStatus.TimeLimit"/>.)</summary>
    public class SolverTimeLimitException : TilePatternException
    {
        public SolverTimeLimitException(string nativeMessage) : base(TilePatternStatus.TimeLimit, nativeMessage) { }
    }

    /// <summary>TP_NOT_AVAILABLE: the stage is not in this build of the library.</summary>
    public class NotAvailableException : TilePatternException
    {
        public NotAvailableException(string nativeMessage) : base(TilePatternStatus.NotAvailable, nativeMessage) { }
    }

    /// <summary>TP_PANIC: a bug in the library, caught at the boundary; the process is intact.</summary>
    public class NativePanicException : TilePatternException
    {
        public NativePanicException(string nativeMessage) : base(TilePatternStatus.Panic, nativeMessage) { }
    }

    /// <summary>TP_CANCELLED, or a cancellation noticed before the call. Derives from
    /// <see cref="System.OperationCanceledException"/> so that the usual
    /// <c>catch (OperationCanceledException)</c> sees it, and carries the token that cancelled.</summary>
    public class TilePatternCanceledException : OperationCanceledException, ITilePatternError
    {
        public TilePatternCanceledException(string nativeMessage, CancellationToken token)
            : base(TilePatternException.Describe(TilePatternStatus.Cancelled, nativeMessage), token)
        {
            NativeMessage = nativeMessage ?? "";
        }

        public TilePatternStatus Status { get { return TilePatternStatus.Cancelled; } }

        public string NativeMessage { get; private set; }
    }

    /// <summary>Status checks and the thread's last error message.</summary>
    internal static class Native
    {
        static readonly object Gate = new object();
        static bool ready;

        /// <summary>Loads the library and checks its ABI version, once. Throws
        /// DllNotFoundException (with what the loader tried) or NotAvailableException.
        /// Call it first in every public entry point, and keep the P/Invokes out of the entry
        /// point itself (see NativeLibraryLoader: Mono binds P/Invokes when it compiles the
        /// calling method).</summary>
        internal static void EnsureReady()
        {
            lock (Gate)
            {
                if (ready)
                    return;
                NativeLibraryLoader.EnsureLoaded();
                uint abi;
                try
                {
                    abi = AbiVersion();
                }
                catch (DllNotFoundException e)
                {
                    throw new DllNotFoundException(
                        "The TilePattern native library (" + NativeLibraryLoader.FileName + ") was not found. Put it in runtimes/<rid>/native/ next to TilePattern.dll or set "
                        + NativeLibraryLoader.EnvironmentVariable + ". Loader: " + NativeLibraryLoader.Description.Replace(Environment.NewLine, "; "), e);
                }
                if (abi != NativeMethods.TP_ABI_VERSION)
                    throw new NotAvailableException("the native library has ABI version " + abi + ", this wrapper needs " + NativeMethods.TP_ABI_VERSION);
                ready = true;
            }
        }

        [MethodImpl(MethodImplOptions.NoInlining)]
        internal static uint AbiVersion()
        {
            return NativeMethods.tp_abi_version();
        }

        [MethodImpl(MethodImplOptions.NoInlining)]
        internal static string Version()
        {
            return Marshal.PtrToStringAnsi(NativeMethods.tp_version());
        }

        /// <summary>tp_last_error_message() of this thread, as UTF-8 text.</summary>
        [MethodImpl(MethodImplOptions.NoInlining)]
        internal static string LastErrorMessage()
        {
            int length = checked((int)NativeMethods.tp_last_error_message(null, UIntPtr.Zero).ToUInt64());
            if (length == 0)
                return "";
            var buffer = new byte[length + 1];
            int full = checked((int)NativeMethods.tp_last_error_message(buffer, (UIntPtr)buffer.Length).ToUInt64());
            return Encoding.UTF8.GetString(buffer, 0, Math.Min(full, length));
        }

        /// <summary>Throws the exception for a failure status (reading the message first).</summary>
        internal static void Check(int status)
        {
            if (status == (int)TilePatternStatus.Ok)
                return;
            throw ToException(status, LastErrorMessage(), CancellationToken.None);
        }

        internal static Exception ToException(int status, string message, CancellationToken token)
        {
            switch ((TilePatternStatus)status)
            {
                case TilePatternStatus.NullPointer: return new NullPointerException(message);
                case TilePatternStatus.InvalidArgument: return new InvalidArgumentException(message);
                case TilePatternStatus.BufferTooSmall: return new BufferTooSmallException(message);
                case TilePatternStatus.InvalidMesh: return new InvalidMeshException(message);
                case TilePatternStatus.InvalidPattern: return new InvalidPatternException(message);
                case TilePatternStatus.SolverFailed: return new SolverFailedException(message);
                case TilePatternStatus.TimeLimit: return new SolverTimeLimitException(message);
                case TilePatternStatus.Cancelled: return new TilePatternCanceledException(message, token);
                case TilePatternStatus.NotAvailable: return new NotAvailableException(message);
                case TilePatternStatus.Panic: return new NativePanicException(message);
                default:
                    // A status newer than this wrapper: still an error, with its number.
                    return new TilePatternException((TilePatternStatus)status, message);
            }
        }

        internal static UIntPtr Size(int n)
        {
            return (UIntPtr)(ulong)n;
        }

        internal static int Count(UIntPtr n)
        {
            return checked((int)n.ToUInt64());
        }
    }
}

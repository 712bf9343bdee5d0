// Bridges the native progress callback to IProgress<double> and CancellationToken.
//
// The library calls the callback on the thread that called the stage. The callback must never
// let an exception unwind through the native frames (undefined behaviour), so it catches
// everything, asks the library to stop, and Finish rethrows once the native call has returned.
using System;
using System.Runtime.ExceptionServices;
using System.Threading;

namespace TilePattern
{
    internal sealed class ProgressBridge
    {
        readonly IProgress<double> progress;
        readonly CancellationToken token;
        readonly TpProgressCallback callback;
        ExceptionDispatchInfo failure;
        int calls;

        public ProgressBridge(IProgress<double> progress, CancellationToken token)
        {
            this.progress = progress;
            this.token = token;
            callback = OnProgress;
        }

        /// <summary>The delegate to pass, or null when there is nobody to report to and nothing to cancel.</summary>
        public TpProgressCallback Callback
        {
            get { return progress == null && !token.CanBeCanceled ? null : callback; }
        }

        /// <summary>How many times the library called back.</summary>
        public int Calls { get { return calls; } }

        /// <summary>Throws before the call if the token is already cancelled.</summary>
        public void ThrowIfCancelled()
        {
            if (token.IsCancellationRequested)
                throw new TilePatternCanceledException("cancelled before the call", token);
        }

        int OnProgress(IntPtr user, uint stage, double fraction)
        {
            try
            {
                calls++;
                if (failure != null || token.IsCancellationRequested)
                    return 1;
                if (progress != null)
                    progress.Report(fraction);
                return token.IsCancellationRequested ? 1 : 0;
            }
            catch (Exception e)
            {
                failure = ExceptionDispatchInfo.Capture(e);
                return 1;
            }
        }

        /// <summary>After the native call: keeps the delegate alive up to here, rethrows an
        /// exception from the progress sink, and maps the status (TP_CANCELLED with this token).</summary>
        public void Finish(int status)
        {
            GC.KeepAlive(callback);
            if (failure != null)
                failure.Throw();
            if (status == (int)TilePatternStatus.Ok)
                return;
            string message = Native.LastErrorMessage();
            throw Native.ToException(status, message, token);
        }
    }
}

// Solves off the host's UI thread: one background job per solve slot (a Grasshopper
// component's iteration), keyed by a fingerprint of its inputs. The host asks for each slot's
// state on every solution pass; a slot whose inputs changed gets its old job cancelled and a
// new one started, a slot no longer asked for is cancelled, and the host is told (on the worker
// thread) when a job ends so that it can schedule a new pass, and every so often how far the
// running jobs are. Nothing here touches the host's document: the work runs on what the host
// copied out of it.
using System;
using System.Collections.Generic;
using System.Diagnostics;
using System.Globalization;
using System.Threading;
using System.Threading.Tasks;

namespace TilePattern
{
    /// <summary>Where a background job is.</summary>
    public enum JobState
    {
        /// <summary>Started and not finished.</summary>
        Running,
        /// <summary>Finished with a result.</summary>
        Done,
        /// <summary>Finished with an exception (<see cref="JobStatus{TResult}.Error"/>).</summary>
        Failed,
        /// <summary>Cancelled on request (<see cref="BackgroundJobs{TResult}.CancelAll"/>); stays
        /// so for the same inputs until <see cref="BackgroundJobs{TResult}.Restart"/>.</summary>
        Cancelled,
    }

    /// <summary>A snapshot of one job.</summary>
    public sealed class JobStatus<TResult>
    {
        internal JobStatus(JobState state, TResult result, Exception error, double progress, string key)
        {
            State = state;
            Result = result;
            Error = error;
            Progress = progress;
            Key = key;
        }

        public JobState State { get; private set; }
        public TResult Result { get; private set; }
        public Exception Error { get; private set; }
        /// <summary>Last fraction reported by the work (0 to 1).</summary>
        public double Progress { get; private set; }
        public string Key { get; private set; }
    }

    /// <summary>The background jobs of one host object (e.g. one Grasshopper component), one per
    /// slot. Thread-safe. Usage per solution pass: <see cref="BeginPass"/>, then
    /// <see cref="Request"/> for every slot (on the UI thread, with inputs already copied out of
    /// the document), then <see cref="EndPass"/>.</summary>
    public sealed class BackgroundJobs<TResult> : IDisposable
    {
        sealed class Job
        {
            public int Slot;
            public string Key;
            public CancellationTokenSource Source;
            public JobState State;
            public TResult Result;
            public Exception Error;
            public double Progress;
            public Task Task;
        }

        readonly object gate = new object();
        readonly Dictionary<int, Job> jobs = new Dictionary<int, Job>();
        readonly HashSet<int> requested = new HashSet<int>();
        readonly Action finished;
        readonly Action progressChanged;
        readonly long progressTicks;
        readonly Stopwatch clock = Stopwatch.StartNew();
        long lastProgress = long.MinValue;
        bool disposed;

        /// <param name="finished">Called on the worker thread when a job that is still current
        /// (its slot still asks for its inputs) ends, done, failed or cancelled on request: the
        /// host schedules a new solution pass there (marshalled to its UI thread).</param>
        /// <param name="progressChanged">Called on a worker thread when a running job reports
        /// progress, at most once per <paramref name="progressIntervalSeconds"/> (may be null).</param>
        /// <param name="progressIntervalSeconds">Least time between two progress calls.</param>
        public BackgroundJobs(Action finished, Action progressChanged = null, double progressIntervalSeconds = 0.5)
        {
            if (finished == null)
                throw new ArgumentNullException("finished");
            this.finished = finished;
            this.progressChanged = progressChanged;
            progressTicks = (long)(Math.Max(0.0, progressIntervalSeconds) * Stopwatch.Frequency);
        }

        /// <summary>Starts a solution pass: slots not requested before <see cref="EndPass"/> are cancelled.</summary>
        public void BeginPass()
        {
            lock (gate)
                requested.Clear();
        }

        /// <summary>The state of <paramref name="slot"/> for inputs <paramref name="key"/>: the
        /// job already there when it has the same key (running, done, failed or cancelled);
        /// otherwise the old job, if any, is cancelled and <paramref name="work"/> starts on a
        /// background thread with a token (cancelled when the inputs change, the slot goes away or
        /// on request) and a progress sink.</summary>
        public JobStatus<TResult> Request(int slot, string key, Func<CancellationToken, IProgress<double>, TResult> work)
        {
            if (key == null)
                throw new ArgumentNullException("key");
            if (work == null)
                throw new ArgumentNullException("work");
            lock (gate)
            {
                if (disposed)
                    throw new ObjectDisposedException("BackgroundJobs");
                requested.Add(slot);
                Job job;
                if (jobs.TryGetValue(slot, out job) && job.Key == key)
                    return Snapshot(job);
                if (job != null)
                    job.Source.Cancel();
                job = new Job { Slot = slot, Key = key, Source = new CancellationTokenSource(), State = JobState.Running };
                jobs[slot] = job;
                Job started = job;
                CancellationToken token = job.Source.Token;
                var progress = new Sink(this, job);
                job.Task = Task.Factory.StartNew(() => Run(started, work, token, progress), CancellationToken.None,
                    TaskCreationOptions.LongRunning, TaskScheduler.Default);
                return Snapshot(job);
            }
        }

        /// <summary>Ends a pass: cancels and forgets the slots that were not requested in it
        /// (the host has fewer iterations now).</summary>
        public void EndPass()
        {
            lock (gate)
            {
                var gone = new List<int>();
                foreach (KeyValuePair<int, Job> entry in jobs)
                    if (!requested.Contains(entry.Key))
                        gone.Add(entry.Key);
                foreach (int slot in gone)
                {
                    jobs[slot].Source.Cancel();
                    jobs.Remove(slot);
                }
            }
        }

        /// <summary>Cancels every running job on request. Their slots report
        /// <see cref="JobState.Cancelled"/> for the same inputs (no restart on the next pass)
        /// until <see cref="Restart"/> or until the inputs change.</summary>
        /// <returns>How many jobs were running.</returns>
        public int CancelAll()
        {
            lock (gate)
            {
                int n = 0;
                foreach (Job job in jobs.Values)
                    if (job.State == JobState.Running)
                    {
                        job.State = JobState.Cancelled;
                        job.Source.Cancel();
                        n++;
                    }
                return n;
            }
        }

        /// <summary>Forgets cancelled and failed jobs, so that the next pass starts them again.</summary>
        public void Restart()
        {
            lock (gate)
            {
                var again = new List<int>();
                foreach (KeyValuePair<int, Job> entry in jobs)
                    if (entry.Value.State == JobState.Cancelled || entry.Value.State == JobState.Failed)
                        again.Add(entry.Key);
                foreach (int slot in again)
                    jobs.Remove(slot);
            }
        }

        /// <summary>Jobs still running.</summary>
        public int RunningCount
        {
            get
            {
                lock (gate)
                {
                    int n = 0;
                    foreach (Job job in jobs.Values)
                        if (job.State == JobState.Running)
                            n++;
                    return n;
                }
            }
        }

        /// <summary>A short status for the host to show: "Solving… 45 %", "Solving 2 of 3… 45 %"
        /// (mean progress of the running jobs), "Cancelled", or "" when nothing is running or
        /// cancelled.</summary>
        public string Summary
        {
            get
            {
                lock (gate)
                {
                    int running = 0, cancelled = 0;
                    double progress = 0;
                    foreach (Job job in jobs.Values)
                    {
                        if (job.State == JobState.Running)
                        {
                            running++;
                            progress += job.Progress;
                        }
                        else if (job.State == JobState.Cancelled)
                            cancelled++;
                    }
                    if (running > 0)
                    {
                        string percent = (100 * progress / running).ToString("0", CultureInfo.InvariantCulture) + " %";
                        return jobs.Count == 1 ? "Solving… " + percent
                            : "Solving " + running.ToString(CultureInfo.InvariantCulture) + " of " + jobs.Count.ToString(CultureInfo.InvariantCulture) + "… " + percent;
                    }
                    return cancelled > 0 ? "Cancelled" : "";
                }
            }
        }

        /// <summary>Waits until no job is running (for shutdown and tests); false on timeout.</summary>
        public bool Wait(int millisecondsTimeout)
        {
            var tasks = new List<Task>();
            lock (gate)
                foreach (Job job in jobs.Values)
                    if (job.Task != null)
                        tasks.Add(job.Task);
            return Task.WaitAll(tasks.ToArray(), millisecondsTimeout);
        }

        /// <summary>Cancels everything; no callback follows.</summary>
        public void Dispose()
        {
            lock (gate)
            {
                disposed = true;
                foreach (Job job in jobs.Values)
                    job.Source.Cancel();
                jobs.Clear();
            }
        }

        void Run(Job job, Func<CancellationToken, IProgress<double>, TResult> work, CancellationToken token, IProgress<double> progress)
        {
            TResult result = default(TResult);
            Exception error = null;
            try
            {
                result = work(token, progress);
            }
            catch (Exception e)
            {
                error = e;
            }
            bool notify;
            lock (gate)
            {
                if (job.State == JobState.Running)
                {
                    if (token.IsCancellationRequested)
                        job.State = JobState.Cancelled;
                    else if (error != null)
                    {
                        job.State = JobState.Failed;
                        job.Error = error;
                    }
                    else
                    {
                        job.State = JobState.Done;
                        job.Result = result;
                        job.Progress = 1.0;
                    }
                }
                Job current;
                notify = !disposed && jobs.TryGetValue(job.Slot, out current) && ReferenceEquals(current, job);
            }
            if (notify)
                finished();
        }

        void Reported(Job job, double fraction)
        {
            bool tell = false;
            lock (gate)
            {
                job.Progress = Math.Max(0.0, Math.Min(1.0, fraction));
                long now = clock.ElapsedTicks;
                if (progressChanged != null && !disposed && job.State == JobState.Running && (lastProgress == long.MinValue || now - lastProgress >= progressTicks))
                {
                    lastProgress = now;
                    tell = true;
                }
            }
            if (tell)
                progressChanged();
        }

        static JobStatus<TResult> Snapshot(Job job)
        {
            return new JobStatus<TResult>(job.State, job.Result, job.Error, job.Progress, job.Key);
        }

        sealed class Sink : IProgress<double>
        {
            readonly BackgroundJobs<TResult> owner;
            readonly Job job;

            public Sink(BackgroundJobs<TResult> owner, Job job)
            {
                this.owner = owner;
                this.job = job;
            }

            public void Report(double value)
            {
                owner.Reported(job, value);
            }
        }
    }
}

// What every TilePattern component shares: the category, error reporting, and Escape-key
// cancellation of the long native calls.
using System;
using System.Threading;
using Grasshopper.Kernel;

namespace TilePattern.Gh
{
    public abstract class ComponentBase : GH_Component
    {
        /// <summary>The ribbon tab of every TilePattern component. (Not named Category: that
        /// would hide GH_InstanceDescription.Category, warning CS0108.)</summary>
        internal const string Tab = "TilePattern";

        protected ComponentBase(string name, string nickname, string description, string subcategory)
            : base(name, nickname, description, Tab, subcategory)
        {
        }

        /// <summary>Runs a step, turning every failure into a runtime message on the component.
        /// Returns false if it failed.</summary>
        protected bool Run(Action step)
        {
            try
            {
                step();
                return true;
            }
            catch (TilePatternCanceledException)
            {
                AddRuntimeMessage(GH_RuntimeMessageLevel.Warning, "Cancelled (Escape).");
                AbortSolution();
            }
            catch (InvalidMeshException e)
            {
                AddRuntimeMessage(GH_RuntimeMessageLevel.Error, "The mesh was refused: " + e.NativeMessage);
            }
            catch (InvalidPatternException e)
            {
                AddRuntimeMessage(GH_RuntimeMessageLevel.Error, "The pattern does not fit this quad mesh (was it solved on another one?): " + e.NativeMessage);
            }
            catch (InvalidArgumentException e)
            {
                AddRuntimeMessage(GH_RuntimeMessageLevel.Error, "Invalid input: " + e.NativeMessage);
            }
            catch (NativePanicException e)
            {
                AddRuntimeMessage(GH_RuntimeMessageLevel.Error, "Internal error in the TilePattern library (please report it): " + e.NativeMessage);
            }
            catch (TilePatternException e)
            {
                AddRuntimeMessage(GH_RuntimeMessageLevel.Error, e.Status + ": " + e.NativeMessage);
            }
            catch (DllNotFoundException e)
            {
                AddRuntimeMessage(GH_RuntimeMessageLevel.Error, e.Message);
            }
            catch (ArgumentException e)
            {
                AddRuntimeMessage(GH_RuntimeMessageLevel.Error, e.Message);
            }
            catch (ObjectDisposedException e)
            {
                AddRuntimeMessage(GH_RuntimeMessageLevel.Error, "The input was released: " + e.Message);
            }
            return false;
        }

        /// <summary>Progress sink for the native calls: polls the Escape key (the library calls
        /// back on this, the UI, thread) and turns a press into a cancellation.</summary>
        protected sealed class EscapeWatcher : IProgress<double>, IDisposable
        {
            readonly CancellationTokenSource source = new CancellationTokenSource();

            public CancellationToken Token { get { return source.Token; } }

            public void Report(double fraction)
            {
                if (GH_Document.IsEscapeKeyDown())
                    source.Cancel();
            }

            public void Dispose()
            {
                source.Dispose();
            }
        }

        /// <summary>After a cancelled step: stops the rest of the solution too.</summary>
        protected void AbortSolution()
        {
            GH_Document document = OnPingDocument();
            if (document != null)
                document.RequestAbortSolution();
        }

        protected static T Unwrap<T>(IGH_DataAccess access, int index) where T : class
        {
            object value = null;
            if (!access.GetData(index, ref value) || value == null)
                return null;
            // A generic parameter hands over its items wrapped (GH_ObjectWrapper): the wrapped
            // object is the goo's script variable.
            var goo = value as Grasshopper.Kernel.Types.IGH_Goo;
            return (goo != null ? goo.ScriptVariable() : value) as T;
        }
    }
}

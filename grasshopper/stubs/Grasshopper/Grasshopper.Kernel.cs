// Reference stub of Grasshopper (Grasshopper.dll): exactly the members the TilePattern
// components use, with the real names, namespaces and signatures. Public members are checked
// by scripts/check-gh-stubs.py against the published type stubs of Grasshopper 7 and 8;
// protected members, nested and generic types and virtual/abstract/override modifiers, which
// those stubs do not show, against ledger.txt (from the SDK documentation). Compiled into
// target/gh/Grasshopper.dll for `make gh-compile`; never shipped. Bodies are empty.
using System;
using System.Collections;
using System.Collections.Generic;
using System.Drawing;
using System.Windows.Forms;
using Rhino.Geometry;

namespace Grasshopper.Kernel
{
    public enum GH_Exposure
    {
        primary = 2,
        secondary = 4,
    }

    public enum GH_RuntimeMessageLevel
    {
        Blank = 0,
        Warning = 10,
        Error = 20,
        Remark = 255,
    }

    public enum GH_ParamAccess
    {
        item = 0,
        list = 1,
        tree = 2,
    }

    public enum GH_DocumentContext
    {
        Unknown = 0,
        None = 1,
        Open = 2,
        Close = 3,
        Loaded = 4,
        Unloaded = 5,
        Lock = 6,
        Unlock = 7,
    }

    public delegate void GH_ScheduleDelegate(GH_Document doc);

    public abstract class GH_InstanceDescription
    {
        internal GH_InstanceDescription() { }
    }

    public abstract class GH_DocumentObject : GH_InstanceDescription
    {
        internal GH_DocumentObject() { }
        public abstract Guid ComponentGuid { get; }
        public virtual GH_Exposure Exposure { get { throw null; } }
        protected virtual Bitmap Icon { get { throw null; } }
        public GH_Document OnPingDocument() { throw null; }
        public void ExpireSolution(bool recompute) { }
        public void OnDisplayExpired(bool redraw) { }
        public virtual void RemovedFromDocument(GH_Document document) { }
        public virtual void DocumentContextChanged(GH_Document document, GH_DocumentContext context) { }
        public static ToolStripMenuItem Menu_AppendItem(ToolStrip menu, string text, EventHandler click, bool enabled) { throw null; }
    }

    public abstract class GH_ActiveObject : GH_DocumentObject
    {
        internal GH_ActiveObject() { }
        public void AddRuntimeMessage(GH_RuntimeMessageLevel level, string text) { }
    }

    public abstract class GH_Component : GH_ActiveObject
    {
        protected GH_Component(string name, string nickname, string description, string category, string subCategory) { }
        protected abstract void RegisterInputParams(GH_InputParamManager pManager);
        protected abstract void RegisterOutputParams(GH_OutputParamManager pManager);
        protected abstract void SolveInstance(IGH_DataAccess DA);
        protected virtual void BeforeSolveInstance() { }
        protected virtual void AfterSolveInstance() { }
        protected virtual void AppendAdditionalComponentMenuItems(ToolStripDropDown menu) { }
        protected static double DocumentTolerance() { throw null; }
        public virtual BoundingBox ClippingBox { get { throw null; } }
        public virtual void DrawViewportMeshes(IGH_PreviewArgs args) { }
        public override void RemovedFromDocument(GH_Document document) { }
        public override void DocumentContextChanged(GH_Document document, GH_DocumentContext context) { }
        public string Message { get { throw null; } set { } }
        public GH_ComponentParamServer Params { get { throw null; } }

        public class GH_InputParamManager
        {
            internal GH_InputParamManager() { }
            public IGH_Param this[int index] { get { throw null; } }
            public int AddMeshParameter(string name, string nickname, string description, GH_ParamAccess access) { throw null; }
            public int AddNumberParameter(string name, string nickname, string description, GH_ParamAccess access) { throw null; }
            public int AddNumberParameter(string name, string nickname, string description, GH_ParamAccess access, double @default) { throw null; }
            public int AddIntegerParameter(string name, string nickname, string description, GH_ParamAccess access) { throw null; }
            public int AddIntegerParameter(string name, string nickname, string description, GH_ParamAccess access, int @default) { throw null; }
            public int AddVectorParameter(string name, string nickname, string description, GH_ParamAccess access) { throw null; }
            public int AddCurveParameter(string name, string nickname, string description, GH_ParamAccess access) { throw null; }
            public int AddBooleanParameter(string name, string nickname, string description, GH_ParamAccess access, bool @default) { throw null; }
            public int AddGenericParameter(string name, string nickname, string description, GH_ParamAccess access) { throw null; }
        }

        public class GH_OutputParamManager
        {
            internal GH_OutputParamManager() { }
            public int AddMeshParameter(string name, string nickname, string description, GH_ParamAccess access) { throw null; }
            public int AddNumberParameter(string name, string nickname, string description, GH_ParamAccess access) { throw null; }
            public int AddIntegerParameter(string name, string nickname, string description, GH_ParamAccess access) { throw null; }
            public int AddGenericParameter(string name, string nickname, string description, GH_ParamAccess access) { throw null; }
            public int AddTextParameter(string name, string nickname, string description, GH_ParamAccess access) { throw null; }
            public int AddBrepParameter(string name, string nickname, string description, GH_ParamAccess access) { throw null; }
            public int AddPlaneParameter(string name, string nickname, string description, GH_ParamAccess access) { throw null; }
        }
    }

    public class GH_ComponentParamServer
    {
        internal GH_ComponentParamServer() { }
        public List<IGH_Param> Input { get { throw null; } }
    }

    public interface IGH_Param
    {
        bool Optional { get; set; }
    }

    public interface IGH_DataAccess
    {
        int Iteration { get; }
        Grasshopper.Kernel.Data.GH_Path ParameterTargetPath(int paramIndex);
        int ParameterTargetIndex(int paramIndex);
        bool GetData<T>(int index, ref T destination);
        bool GetDataList<T>(int index, List<T> list);
        bool SetData(int paramIndex, object data);
        bool SetDataList(int paramIndex, IEnumerable data);
        bool SetDataTree(int paramIndex, Grasshopper.Kernel.Data.IGH_DataTree tree);
    }

    public interface IGH_PreviewArgs
    {
        Rhino.Display.DisplayPipeline Display { get; }
    }

    public class GH_Document
    {
        internal GH_Document() { }
        public void ScheduleSolution(int delay, GH_ScheduleDelegate callback) { }
    }

    public class GH_ComponentServer
    {
        internal GH_ComponentServer() { }
        public GH_AssemblyInfo FindAssembly(Guid libraryId) { throw null; }
    }

    public abstract class GH_AssemblyInfo
    {
        protected GH_AssemblyInfo() { }
        public virtual string Name { get { throw null; } }
        public virtual string Description { get { throw null; } }
        public virtual Guid Id { get { throw null; } }
        public virtual Bitmap Icon { get { throw null; } }
        public virtual string AuthorName { get { throw null; } }
        public virtual string AuthorContact { get { throw null; } }
        public virtual string Version { get { throw null; } }
        public string Location { get { throw null; } }
    }
}

namespace Grasshopper.Kernel.Parameters
{
    public class Param_Number
    {
        public Param_Number() { }
        public bool AngleParameter { get { throw null; } set { } }
        public bool UseDegrees { get { throw null; } }
    }

    public class Param_Integer
    {
        public Param_Integer() { }
        public void AddNamedValue(string name, int value) { }
    }
}

namespace Grasshopper.Kernel.Data
{
    public interface IGH_DataTree
    {
    }

    public class GH_Path
    {
        public GH_Path(params int[] args) { }
        public int[] Indices { get { throw null; } }
    }
}

namespace Grasshopper.Kernel.Types
{
    public interface IGH_Goo
    {
        object ScriptVariable();
    }
}

namespace Grasshopper
{
    public class Instances
    {
        Instances() { }
        public static Grasshopper.Kernel.GH_ComponentServer ComponentServer { get { throw null; } }
    }

    public class DataTree<T> : Grasshopper.Kernel.Data.IGH_DataTree
    {
        public DataTree() { }
        public void AddRange(IEnumerable<T> data, Grasshopper.Kernel.Data.GH_Path path) { }
    }
}

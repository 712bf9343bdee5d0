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

    public enum GH_LoadingInstruction
    {
        Proceed = 0,
        Abort = 1,
    }

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
        public virtual BoundingBox ClippingBox { get { throw null; } }
        public virtual void DrawViewportMeshes(IGH_PreviewArgs args) { }

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

    public interface IGH_Param
    {
        bool Optional { get; set; }
    }

    public interface IGH_DataAccess
    {
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
        public static bool IsEscapeKeyDown() { throw null; }
        public void RequestAbortSolution() { }
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
    }

    public abstract class GH_AssemblyPriority
    {
        protected GH_AssemblyPriority() { }
        public abstract GH_LoadingInstruction PriorityLoad();
    }
}

namespace Grasshopper.Kernel.Data
{
    public interface IGH_DataTree
    {
    }

    public sealed class GH_Path
    {
        public GH_Path(int index) { }
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
    public class DataTree<T> : Grasshopper.Kernel.Data.IGH_DataTree
    {
        public DataTree() { }
        public void AddRange(IEnumerable<T> data, Grasshopper.Kernel.Data.GH_Path path) { }
    }
}

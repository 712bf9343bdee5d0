// Reference stub of RhinoCommon's Rhino.Display (see Rhino.cs).
using System;
using System.Drawing;

namespace Rhino.Display
{
    public class DisplayMaterial
    {
        public DisplayMaterial(Color diffuse) { }
    }

    public class DisplayPipeline
    {
        internal DisplayPipeline() { }
        public void DrawBrepShaded(Rhino.Geometry.Brep brep, DisplayMaterial material) { }
    }
}

// Reference stub of RhinoCommon: exactly the members the TilePattern components use, with the
// real names, namespaces and signatures (checked by scripts/check-gh-stubs.py against the
// published type stubs of RhinoCommon 7 and 8). Compiled into target/gh/RhinoCommon.dll for
// `make gh-compile`; never shipped (Rhino provides the real assembly). Bodies are empty.
using System;

namespace Rhino
{
    public class RhinoDoc
    {
        RhinoDoc() { }
        public static RhinoDoc ActiveDoc { get { throw null; } }
        public UnitSystem ModelUnitSystem { get { throw null; } }
    }

    public class RhinoApp
    {
        RhinoApp() { }
        public static void InvokeOnUiThread(Delegate method, params object[] args) { }
    }

    public enum UnitSystem
    {
        None = 0, Microns = 1, Millimeters = 2, Centimeters = 3, Meters = 4, Kilometers = 5, Microinches = 6,
        Mils = 7, Inches = 8, Feet = 9, Miles = 10, CustomUnits = 11, Angstroms = 12, Nanometers = 13,
        Decimeters = 14, Dekameters = 15, Hectometers = 16, Megameters = 17, Gigameters = 18, Yards = 19,
        PrinterPoints = 20, PrinterPicas = 21, NauticalMiles = 22, AstronomicalUnits = 23, LightYears = 24,
        Parsecs = 25, Unset = 255,
    }
}

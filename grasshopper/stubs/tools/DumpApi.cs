// Lists every public and protected member that the stub assemblies declare, one JSON object a
// line, for scripts/check-gh-stubs.py to compare with the published type stubs. Reads the
// compiled assemblies (not the C# text), so what is checked is what the components compile
// against. Usage: mono DumpApi.exe RhinoCommon.dll Grasshopper.dll
using System;
using System.Collections.Generic;
using System.Linq;
using System.Reflection;
using System.Text;

static class DumpApi
{
    const BindingFlags Declared = BindingFlags.DeclaredOnly | BindingFlags.Public | BindingFlags.NonPublic
        | BindingFlags.Instance | BindingFlags.Static;

    static int Main(string[] args)
    {
        foreach (string path in args)
        {
            Assembly assembly = Assembly.LoadFrom(path);
            foreach (Type type in assembly.GetTypes().OrderBy(t => t.FullName, StringComparer.Ordinal))
            {
                if (!(type.IsPublic || type.IsNestedPublic))
                    continue;
                DumpType(assembly.GetName().Name, type);
            }
        }
        return 0;
    }

    static void DumpType(string assembly, Type type)
    {
        string kind = type.IsEnum ? "enum" : type.IsInterface ? "interface" : type.IsValueType ? "struct"
            : typeof(Delegate).IsAssignableFrom(type) ? "delegate" : "class";
        var bases = new List<string>();
        if (type.BaseType != null && type.BaseType != typeof(object) && type.BaseType != typeof(ValueType)
            && type.BaseType != typeof(Enum) && type.BaseType != typeof(MulticastDelegate))
            bases.Add(Name(type.BaseType));
        foreach (Type i in type.GetInterfaces())
            bases.Add(Name(i));
        var o = new Obj();
        o.Add("assembly", assembly).Add("kind", "type").Add("type", TypeKey(type)).Add("namespace", type.Namespace)
            .Add("declared", kind).Add("nested", type.IsNested).Add("generic", type.IsGenericTypeDefinition)
            .Add("abstract", type.IsAbstract && !type.IsSealed).Add("static", type.IsAbstract && type.IsSealed)
            .Add("bases", bases);
        Console.WriteLine(o);

        if (type.IsEnum)
        {
            foreach (FieldInfo f in type.GetFields(BindingFlags.Public | BindingFlags.Static))
                Console.WriteLine(new Obj().Add("kind", "enumvalue").Add("type", TypeKey(type)).Add("name", f.Name)
                    .Add("value", Convert.ToInt64(f.GetRawConstantValue())).ToString());
            return;
        }
        if (kind == "delegate")
        {
            MethodInfo invoke = type.GetMethod("Invoke");
            Console.WriteLine(Member("delegate", type, invoke, "Invoke").Add("returns", Name(invoke.ReturnType)).ToString());
            return;
        }
        foreach (ConstructorInfo c in type.GetConstructors(Declared))
            if (Visible(c))
                Console.WriteLine(Member("constructor", type, c, "__init__").ToString());
        foreach (MethodInfo m in type.GetMethods(Declared))
        {
            if (!Visible(m) || m.IsSpecialName)
                continue;
            Console.WriteLine(Member("method", type, m, m.Name).Add("returns", Name(m.ReturnType))
                .Add("generic_arguments", m.IsGenericMethodDefinition ? m.GetGenericArguments().Select(a => a.Name).ToList() : new List<string>()).ToString());
        }
        foreach (PropertyInfo p in type.GetProperties(Declared))
        {
            MethodInfo get = p.GetGetMethod(true), set = p.GetSetMethod(true);
            MethodInfo any = get != null && Visible(get) ? get : set;
            if (any == null || !Visible(any))
                continue;
            bool indexer = p.GetIndexParameters().Length > 0;
            var o2 = Member(indexer ? "indexer" : "property", type, any, p.Name);
            o2.Add("returns", Name(p.PropertyType)).Add("get", get != null && Visible(get)).Add("set", set != null && Visible(set));
            if (indexer)
                o2.Add("parameters", p.GetIndexParameters().Select(Parameter).ToList());
            Console.WriteLine(o2);
        }
        foreach (FieldInfo f in type.GetFields(Declared))
            if (f.IsPublic || f.IsFamily || f.IsFamilyOrAssembly)
                Console.WriteLine(new Obj().Add("kind", "field").Add("type", TypeKey(type)).Add("name", f.Name)
                    .Add("returns", Name(f.FieldType)).Add("static", f.IsStatic).Add("access", f.IsPublic ? "public" : "protected")
                    .Add("readonly", f.IsInitOnly || f.IsLiteral).ToString());
    }

    static bool Visible(MethodBase m)
    {
        return m.IsPublic || m.IsFamily || m.IsFamilyOrAssembly;
    }

    static Obj Member(string kind, Type type, MethodBase m, string name)
    {
        var mi = m as MethodInfo;
        bool isOverride = mi != null && mi.IsVirtual && mi.GetBaseDefinition().DeclaringType != mi.DeclaringType;
        string modifier = m.IsAbstract ? "abstract" : isOverride ? (m.IsFinal ? "sealed override" : "override")
            : m.IsVirtual && !m.IsFinal && !type.IsInterface ? "virtual" : "";
        if (type.IsInterface || typeof(Delegate).IsAssignableFrom(type))
            modifier = "";
        return new Obj().Add("kind", kind).Add("type", TypeKey(type)).Add("name", name)
            .Add("access", m.IsPublic ? "public" : "protected").Add("static", m.IsStatic).Add("modifier", modifier)
            .Add("parameters", m.GetParameters().Select(Parameter).ToList());
    }

    static Obj Parameter(ParameterInfo p)
    {
        Type t = p.ParameterType;
        string mode = "";
        if (t.IsByRef)
        {
            mode = p.IsOut ? "out" : "ref";
            t = t.GetElementType();
        }
        else if (p.GetCustomAttributes(typeof(ParamArrayAttribute), false).Length > 0)
            mode = "params";
        return new Obj().Add("name", p.Name).Add("type", Name(t)).Add("mode", mode).Add("optional", p.IsOptional);
    }

    static string TypeKey(Type t)
    {
        return t.IsNested ? TypeKey(t.DeclaringType) + "+" + t.Name : t.Namespace + "." + t.Name;
    }

    /// <summary>C# spelling with namespaces: System.Collections.Generic.IEnumerable&lt;Rhino.Geometry.Point3d&gt;.</summary>
    static string Name(Type t)
    {
        if (t.IsGenericParameter)
            return t.Name;
        if (t.IsArray)
            return Name(t.GetElementType()) + "[]";
        string name = t.IsNested ? Name(t.DeclaringType) + "+" + t.Name : t.Namespace + "." + t.Name;
        if (!t.IsGenericType)
            return name;
        name = name.Substring(0, name.IndexOf('`'));
        return name + "<" + string.Join(",", t.GetGenericArguments().Select(Name).ToArray()) + ">";
    }

    /// <summary>A JSON object written in order.</summary>
    sealed class Obj
    {
        readonly StringBuilder text = new StringBuilder();

        public Obj Add(string key, object value)
        {
            text.Append(text.Length == 0 ? "{" : ", ").Append(Quote(key)).Append(": ").Append(Value(value));
            return this;
        }

        static string Value(object value)
        {
            if (value == null) return "null";
            if (value is bool) return (bool)value ? "true" : "false";
            if (value is long || value is int) return Convert.ToString(value, System.Globalization.CultureInfo.InvariantCulture);
            if (value is Obj) return value.ToString();
            if (value is string) return Quote((string)value);
            var list = value as System.Collections.IEnumerable;
            var items = new List<string>();
            foreach (object item in list)
                items.Add(Value(item));
            return "[" + string.Join(", ", items.ToArray()) + "]";
        }

        static string Quote(string s)
        {
            var b = new StringBuilder("\"");
            foreach (char c in s)
            {
                if (c == '"' || c == '\\') b.Append('\\').Append(c);
                else if (c < ' ') b.AppendFormat("\\u{0:x4}", (int)c);
                else b.Append(c);
            }
            return b.Append('"').ToString();
        }

        public override string ToString()
        {
            return text.Length == 0 ? "{}" : text.ToString() + "}";
        }
    }
}

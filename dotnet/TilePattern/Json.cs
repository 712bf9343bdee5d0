// A small JSON reader for the report (netstandard2.0 has no JSON library without NuGet, and
// mono's DataContractJsonSerializer lives in an assembly Debian's mono does not install).
// Objects become Dictionary<string, object>, arrays List<object>, numbers double, strings
// string, true/false bool, null null.
using System;
using System.Collections.Generic;
using System.Globalization;
using System.Text;

namespace TilePattern
{
    internal sealed class JsonReader
    {
        readonly string text;
        int at;

        JsonReader(string text)
        {
            this.text = text;
        }

        /// <summary>Parses one JSON value; throws FormatException on malformed input.</summary>
        public static object Parse(string text)
        {
            if (text == null)
                throw new ArgumentNullException("text");
            var reader = new JsonReader(text);
            object value = reader.Value();
            reader.SkipSpace();
            if (reader.at != text.Length)
                throw reader.Error("unexpected text after the value");
            return value;
        }

        FormatException Error(string what)
        {
            return new FormatException("JSON: " + what + " at offset " + at);
        }

        void SkipSpace()
        {
            while (at < text.Length && (text[at] == ' ' || text[at] == '\t' || text[at] == '\n' || text[at] == '\r'))
                at++;
        }

        char Peek()
        {
            SkipSpace();
            if (at >= text.Length)
                throw Error("unexpected end");
            return text[at];
        }

        void Expect(char c)
        {
            if (Peek() != c)
                throw Error("expected '" + c + "'");
            at++;
        }

        object Value()
        {
            char c = Peek();
            switch (c)
            {
                case '{': return Object();
                case '[': return Array();
                case '"': return String();
                case 't': Word("true"); return true;
                case 'f': Word("false"); return false;
                case 'n': Word("null"); return null;
                default:
                    if (c == '-' || (c >= '0' && c <= '9'))
                        return Number();
                    throw Error("unexpected character '" + c + "'");
            }
        }

        void Word(string word)
        {
            if (string.CompareOrdinal(text, at, word, 0, word.Length) != 0)
                throw Error("expected " + word);
            at += word.Length;
        }

        Dictionary<string, object> Object()
        {
            var result = new Dictionary<string, object>();
            Expect('{');
            if (Peek() == '}')
            {
                at++;
                return result;
            }
            while (true)
            {
                if (Peek() != '"')
                    throw Error("expected a key");
                string key = String();
                Expect(':');
                result[key] = Value();
                char c = Peek();
                at++;
                if (c == '}')
                    return result;
                if (c != ',')
                    throw Error("expected ',' or '}'");
            }
        }

        List<object> Array()
        {
            var result = new List<object>();
            Expect('[');
            if (Peek() == ']')
            {
                at++;
                return result;
            }
            while (true)
            {
                result.Add(Value());
                char c = Peek();
                at++;
                if (c == ']')
                    return result;
                if (c != ',')
                    throw Error("expected ',' or ']'");
            }
        }

        string String()
        {
            Expect('"');
            var sb = new StringBuilder();
            while (true)
            {
                if (at >= text.Length)
                    throw Error("unterminated string");
                char c = text[at++];
                if (c == '"')
                    return sb.ToString();
                if (c != '\\')
                {
                    sb.Append(c);
                    continue;
                }
                if (at >= text.Length)
                    throw Error("unterminated escape");
                char e = text[at++];
                switch (e)
                {
                    case '"': sb.Append('"'); break;
                    case '\\': sb.Append('\\'); break;
                    case '/': sb.Append('/'); break;
                    case 'b': sb.Append('\b'); break;
                    case 'f': sb.Append('\f'); break;
                    case 'n': sb.Append('\n'); break;
                    case 'r': sb.Append('\r'); break;
                    case 't': sb.Append('\t'); break;
                    case 'u':
                        if (at + 4 > text.Length)
                            throw Error("short \\u escape");
                        sb.Append((char)int.Parse(text.Substring(at, 4), NumberStyles.HexNumber, CultureInfo.InvariantCulture));
                        at += 4;
                        break;
                    default:
                        throw Error("bad escape '\\" + e + "'");
                }
            }
        }

        double Number()
        {
            int start = at;
            if (text[at] == '-')
                at++;
            while (at < text.Length && "0123456789.eE+-".IndexOf(text[at]) >= 0)
                at++;
            double value;
            if (!double.TryParse(text.Substring(start, at - start), NumberStyles.Float, CultureInfo.InvariantCulture, out value))
                throw Error("bad number");
            return value;
        }
    }

    /// <summary>Typed access to parsed JSON objects; missing or null numbers read as NaN.</summary>
    internal static class JsonAccess
    {
        public static Dictionary<string, object> Object(Dictionary<string, object> o, string key)
        {
            object v;
            return o != null && o.TryGetValue(key, out v) ? v as Dictionary<string, object> : null;
        }

        public static double Number(Dictionary<string, object> o, string key)
        {
            object v;
            if (o != null && o.TryGetValue(key, out v) && v is double)
                return (double)v;
            return double.NaN;
        }

        public static int Integer(Dictionary<string, object> o, string key)
        {
            double v = Number(o, key);
            return double.IsNaN(v) ? -1 : checked((int)v);
        }

        /// <summary>The boolean at <paramref name="key"/>; false when absent or not a boolean.</summary>
        public static bool Flag(Dictionary<string, object> o, string key)
        {
            object v;
            return o != null && o.TryGetValue(key, out v) && v is bool && (bool)v;
        }

        public static string Text(Dictionary<string, object> o, string key)
        {
            object v;
            return o != null && o.TryGetValue(key, out v) ? v as string : null;
        }
    }
}

// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// makedna: reads the serialization structs (the *Data structs) of Caliber's headers and writes
//   1. the DNA tables the serializer turns into the file's SDNA block (names, types, structs), and
//   2. a list of every struct and field, from which a test checks offsetof and sizeof against the
//      sizes the DNA implies (no hidden padding).
// Usage: makedna [--check] <table.inc> <fields.inc> [--also Name]... [--skip Name]... header...
// With --check nothing is written: the exit status says whether both files are up to date.
// A struct is read when its name ends in "Data" or "Data2" or is named by --also, and --skip does
// not name it. Each field is one
// declaration `type name;`, `type *name;` or `type name[N]...;` of a basic type (char, short, int,
// float, double, void) or another struct; anything else is an error, so the DNA never silently
// drops a field.
#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace
{
struct Field
{
	std::string type;
	std::string name;    // with '*' prefix and [N] suffixes, as the DNA stores it
	std::string member;  // the bare member name
};

struct Struct
{
	std::string name;
	std::vector<Field> fields;
	std::string file;
};

const char* const kBasicTypes[] = {"char", "uchar", "short", "ushort", "int",
                                   "long", "ulong", "float", "double", "void"};

[[noreturn]] void fail(const std::string& message)
{
	std::fprintf(stderr, "makedna: %s\n", message.c_str());
	std::exit(2);
}

std::string readFile(const std::string& path)
{
	std::ifstream in(path, std::ios::binary);
	if (!in) fail("cannot read " + path);
	std::stringstream ss;
	ss << in.rdbuf();
	return ss.str();
}

// Comments and preprocessor lines carry no fields.
std::string stripComments(const std::string& text)
{
	std::string out;
	out.reserve(text.size());
	size_t i = 0;
	bool lineStart = true;
	while (i < text.size())
	{
		if (text.compare(i, 2, "//") == 0)
		{
			while (i < text.size() && text[i] != '\n') ++i;
			continue;
		}
		if (text.compare(i, 2, "/*") == 0)
		{
			const size_t end = text.find("*/", i + 2);
			i = end == std::string::npos ? text.size() : end + 2;
			out += ' ';
			continue;
		}
		if (lineStart && text[i] == '#')
		{
			// A directive may continue over backslash-newlines.
			while (i < text.size() && !(text[i] == '\n' && text[i - 1] != '\\')) ++i;
			continue;
		}
		if (text[i] == '\n')
			lineStart = true;
		else if (!std::isspace(static_cast<unsigned char>(text[i])))
			lineStart = false;
		out += text[i++];
	}
	return out;
}

bool isIdentChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

std::string trim(const std::string& s)
{
	size_t b = 0, e = s.size();
	while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
	while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
	return s.substr(b, e - b);
}

void parseDeclaration(const std::string& declIn, Struct& st)
{
	std::string decl = trim(declIn);
	if (decl.empty()) return;
	size_t pos = 0;
	auto skipSpace = [&]
	{
		while (pos < decl.size() && std::isspace(static_cast<unsigned char>(decl[pos]))) ++pos;
	};
	auto ident = [&]
	{
		skipSpace();
		const size_t start = pos;
		while (pos < decl.size() && isIdentChar(decl[pos])) ++pos;
		return decl.substr(start, pos - start);
	};
	std::string type = ident();
	if (type == "struct") type = ident();
	if (type == "unsigned")
	{
		const std::string base = ident();
		if (base == "char")
			type = "uchar";
		else if (base == "short")
			type = "ushort";
		else
			fail("struct " + st.name + ": unsupported type unsigned " + base);
	}
	if (type.empty()) fail("struct " + st.name + ": cannot read declaration '" + decl + "'");
	// One or more declarators separated by commas.
	while (true)
	{
		skipSpace();
		std::string stars;
		while (pos < decl.size() && (decl[pos] == '*' || std::isspace(static_cast<unsigned char>(decl[pos]))))
		{
			if (decl[pos] == '*') stars += '*';
			++pos;
		}
		const std::string member = ident();
		if (member.empty()) fail("struct " + st.name + ": no field name in '" + decl + "'");
		std::string dims;
		skipSpace();
		while (pos < decl.size() && decl[pos] == '[')
		{
			const size_t close = decl.find(']', pos);
			if (close == std::string::npos) fail("struct " + st.name + ": unclosed [ in '" + decl + "'");
			const std::string count = trim(decl.substr(pos + 1, close - pos - 1));
			if (count.empty() || count.find_first_not_of("0123456789") != std::string::npos)
				fail("struct " + st.name + ": array size must be a number in '" + decl + "'");
			dims += "[" + count + "]";
			pos = close + 1;
			skipSpace();
		}
		st.fields.push_back(Field{type, stars + member + dims, member});
		skipSpace();
		if (pos >= decl.size()) break;
		if (decl[pos] != ',') fail("struct " + st.name + ": cannot read declaration '" + decl + "'");
		++pos;
	}
}

void parseHeader(const std::string& path, const std::set<std::string>& also, const std::set<std::string>& skip,
                 std::vector<Struct>& out)
{
	const std::string text = stripComments(readFile(path));
	size_t pos = 0;
	while ((pos = text.find("struct", pos)) != std::string::npos)
	{
		const bool startOk = pos == 0 || !isIdentChar(text[pos - 1]);
		size_t p = pos + 6;
		pos = p;
		if (!startOk || p >= text.size() || !std::isspace(static_cast<unsigned char>(text[p]))) continue;
		while (p < text.size() && std::isspace(static_cast<unsigned char>(text[p]))) ++p;
		const size_t nameStart = p;
		while (p < text.size() && isIdentChar(text[p])) ++p;
		const std::string name = text.substr(nameStart, p - nameStart);
		while (p < text.size() && std::isspace(static_cast<unsigned char>(text[p]))) ++p;
		if (p >= text.size() || text[p] != '{') continue;  // a declaration or a derived struct
		// "...Data" and Bullet's second double layouts "...Data2".
		auto endsWith = [&](const char* suffix)
		{
			const size_t n = strlen(suffix);
			return name.size() > n && name.compare(name.size() - n, n, suffix) == 0;
		};
		const bool wanted = endsWith("Data") || endsWith("Data2") || also.count(name);
		if (!wanted || skip.count(name)) continue;
		const size_t close = text.find('}', p);
		if (close == std::string::npos) fail(path + ": struct " + name + " is not closed");
		Struct st;
		st.name = name;
		st.file = path;
		const std::string body = text.substr(p + 1, close - p - 1);
		if (body.find('{') != std::string::npos || body.find('(') != std::string::npos)
			fail(path + ": struct " + name + " has members that are not plain fields");
		size_t start = 0, semi;
		while ((semi = body.find(';', start)) != std::string::npos)
		{
			parseDeclaration(body.substr(start, semi - start), st);
			start = semi + 1;
		}
		if (!trim(body.substr(start)).empty()) fail(path + ": struct " + name + ": text after the last field");
		if (st.fields.empty()) fail(path + ": struct " + name + " has no fields");
		out.push_back(st);
		pos = close;
	}
}

std::string quote(const std::string& s) { return "\"" + s + "\""; }

std::string generateTable(const std::vector<Struct>& structs)
{
	std::vector<std::string> types(std::begin(kBasicTypes), std::end(kBasicTypes));
	std::map<std::string, int> typeIndex;
	for (size_t i = 0; i < types.size(); ++i) typeIndex[types[i]] = int(i);
	std::vector<std::string> names;
	std::map<std::string, int> nameIndex;
	auto typeId = [&](const std::string& t)
	{
		auto it = typeIndex.find(t);
		if (it != typeIndex.end()) return it->second;
		types.push_back(t);
		return typeIndex[t] = int(types.size() - 1);
	};
	auto nameId = [&](const std::string& n)
	{
		auto it = nameIndex.find(n);
		if (it != nameIndex.end()) return it->second;
		names.push_back(n);
		return nameIndex[n] = int(names.size() - 1);
	};
	std::ostringstream strc;
	for (const Struct& st : structs)
	{
		strc << "\t" << typeId(st.name) << ", " << st.fields.size() << ",";
		for (const Field& f : st.fields) strc << " " << typeId(f.type) << ", " << nameId(f.name) << ",";
		strc << "  // " << st.name << "\n";
	}
	std::ostringstream out;
	out << "// Generated by tools/makedna from the serialization structs of Caliber's headers. Do not edit:\n"
	       "// change the headers and rebuild the target caliber_makedna_update (docs/serialization.md).\n";
	out << "static const char* const kDnaNames[] = {\n";
	for (const std::string& n : names) out << "\t" << quote(n) << ",\n";
	out << "};\n";
	out << "static const char* const kDnaTypes[] = {\n";
	for (const std::string& t : types) out << "\t" << quote(t) << ",\n";
	out << "};\n";
	out << "// Each struct: its type, its field count, then a (type, name) pair per field.\n";
	out << "static const short kDnaStructs[] = {\n" << strc.str() << "};\n";
	out << "static const int kDnaStructCount = " << structs.size() << ";\n";
	return out.str();
}

std::string generateFieldList(const std::vector<Struct>& structs)
{
	std::ostringstream out;
	out << "// Generated by tools/makedna (see kDnaStructs): every serialization struct and its fields in order.\n";
	for (const Struct& st : structs)
	{
		out << "CALIBER_DNA_STRUCT(" << st.name << ")\n";
		for (const Field& f : st.fields) out << "CALIBER_DNA_FIELD(" << st.name << ", " << f.member << ")\n";
	}
	return out.str();
}

bool sameAsFile(const std::string& path, const std::string& text)
{
	std::ifstream in(path, std::ios::binary);
	if (!in) return false;
	std::stringstream ss;
	ss << in.rdbuf();
	return ss.str() == text;
}

void writeFile(const std::string& path, const std::string& text)
{
	std::ofstream out(path, std::ios::binary);
	if (!out) fail("cannot write " + path);
	out << text;
}
}  // namespace

int main(int argc, char** argv)
{
	bool check = false;
	std::vector<std::string> positional;
	std::set<std::string> also, skip;
	for (int i = 1; i < argc; ++i)
	{
		const std::string arg = argv[i];
		if (arg == "--check")
			check = true;
		else if (arg == "--also" && i + 1 < argc)
			also.insert(argv[++i]);
		else if (arg == "--skip" && i + 1 < argc)
			skip.insert(argv[++i]);
		else
			positional.push_back(arg);
	}
	if (positional.size() < 3) fail("usage: makedna [--check] <table.inc> <fields.inc> [--also Name]... header...");
	std::vector<Struct> structs;
	for (size_t i = 2; i < positional.size(); ++i) parseHeader(positional[i], also, skip, structs);
	std::set<std::string> seen;
	for (const Struct& st : structs)
		if (!seen.insert(st.name).second) fail("struct " + st.name + " is defined twice (" + st.file + ")");
	// A field embedded by value must be a basic type or a struct the DNA describes.
	for (const Struct& st : structs)
		for (const Field& f : st.fields)
		{
			const bool basic =
			    std::find(std::begin(kBasicTypes), std::end(kBasicTypes), f.type) != std::end(kBasicTypes);
			if (f.name[0] != '*' && !basic && !seen.count(f.type))
				fail("struct " + st.name + ": field " + f.member + " has type " + f.type + ", which is no DNA struct");
		}
	const std::string table = generateTable(structs);
	const std::string fields = generateFieldList(structs);
	if (check)
	{
		const bool tableOk = sameAsFile(positional[0], table);
		const bool fieldsOk = sameAsFile(positional[1], fields);
		if (!tableOk) std::fprintf(stderr, "makedna: %s is out of date\n", positional[0].c_str());
		if (!fieldsOk) std::fprintf(stderr, "makedna: %s is out of date\n", positional[1].c_str());
		return tableOk && fieldsOk ? 0 : 1;
	}
	writeFile(positional[0], table);
	writeFile(positional[1], fields);
	std::printf("makedna: %zu structs\n", structs.size());
	return 0;
}

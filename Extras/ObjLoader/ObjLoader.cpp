// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// A small OBJ parser of our own: tinyobjloader (Debian's 2.0.0rc10) reads "v abc 0 0" or "v 0 0" as zeros
// and drops degenerate faces without a line number, so it cannot give the errors the loader promises
// (docs/extras.md, "Why not tinyobjloader").
#include "ObjLoader/ObjLoader.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <string_view>
#include <unordered_map>

#include "LinearMath/btScalar.h"
#include "ObjLoader/PolygonTriangulation.h"

namespace caliber
{
namespace
{
bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

void splitTokens(std::string_view line, std::vector<std::string_view>& tokens)
{
	tokens.clear();
	std::size_t i = 0;
	while (i < line.size())
	{
		while (i < line.size() && isSpace(line[i])) ++i;
		const std::size_t start = i;
		while (i < line.size() && !isSpace(line[i])) ++i;
		if (i > start) tokens.push_back(line.substr(start, i - start));
	}
}

bool isKeyword(std::string_view token)
{
	for (char c : token)
		if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_')) return false;
	return true;
}

// Whole token as a finite number within kObjMaxCoordinate; else a reason in why.
bool parseCoordinate(std::string_view token, double& value, const char*& why)
{
	const char* first = token.data();
	const char* last = first + token.size();
	if (first != last && *first == '+') ++first;  // from_chars does not take a leading '+'
	const std::from_chars_result r = std::from_chars(first, last, value);
	if (r.ec == std::errc::result_out_of_range)
	{
		why = "is out of range";
		return false;
	}
	if (r.ec != std::errc() || r.ptr != last)
	{
		why = "is not a number";
		return false;
	}
	if (!std::isfinite(value))
	{
		why = "is not finite";
		return false;
	}
	if (std::fabs(value) > kObjMaxCoordinate)
	{
		why = "exceeds the largest accepted coordinate (1e15)";
		return false;
	}
	return true;
}

bool parseInteger(std::string_view token, long long& value)
{
	const char* first = token.data();
	const char* last = first + token.size();
	const std::from_chars_result r = std::from_chars(first, last, value);
	return r.ec == std::errc() && r.ptr == last && first != last;
}

// One group while parsing: its triangles as global vertex indices.
struct GroupFaces
{
	std::string name;
	std::vector<int> triangles;
};

class ObjParser
{
public:
	explicit ObjParser(ObjModel& model) : m_model(model) {}

	void parse(std::string_view text)
	{
		std::size_t pos = 0;
		int lineNumber = 0;
		while (pos < text.size() && !m_stopped)
		{
			std::size_t end = text.find('\n', pos);
			if (end == std::string_view::npos) end = text.size();
			++lineNumber;
			parseLine(text.substr(pos, end - pos), lineNumber);
			pos = end + 1;
		}
		finish();
	}

private:
	void error(int line, const std::string& text)
	{
		if (int(m_model.errors.size()) >= kObjMaxErrors)
		{
			m_model.errors.push_back({line, "too many errors; parsing stopped"});
			m_stopped = true;
			return;
		}
		m_model.errors.push_back({line, text});
	}

	void warning(int line, const std::string& text)
	{
		if (int(m_model.warnings.size()) < kObjMaxErrors) m_model.warnings.push_back({line, text});
	}

	void parseLine(std::string_view line, int lineNumber)
	{
		const std::size_t hash = line.find('#');
		if (hash != std::string_view::npos) line = line.substr(0, hash);
		splitTokens(line, m_tokens);
		if (m_tokens.empty()) return;
		const std::string_view keyword = m_tokens[0];
		if (keyword == "v")
			parseVertex(lineNumber);
		else if (keyword == "f")
			parseFace(lineNumber);
		else if (keyword == "g" || keyword == "o")
			selectGroup();
		else if (keyword == "vt" || keyword == "vn" || keyword == "vp" || keyword == "usemtl" || keyword == "mtllib" ||
		         keyword == "s" || keyword == "l" || keyword == "p")
			return;  // texture, normal, material and line data: not needed for collision
		else if (isKeyword(keyword))
			warning(lineNumber, "unknown statement '" + std::string(keyword) + "' ignored");
		else
			error(lineNumber, "not an OBJ statement (the line starts with '" + printable(keyword) + "')");
	}

	static std::string printable(std::string_view token)
	{
		std::string out;
		for (char c : token.substr(0, 16))
		{
			if (c >= 32 && c < 127)
				out += c;
			else
			{
				char buffer[8];
				std::snprintf(buffer, sizeof(buffer), "\\x%02x", unsigned(static_cast<unsigned char>(c)));
				out += buffer;
			}
		}
		return out;
	}

	void parseVertex(int lineNumber)
	{
		const int numbers = int(m_tokens.size()) - 1;
		// x y z, optionally w, or x y z r g b (the common vertex-colour extension), optionally w after them.
		if (numbers < 3 || numbers > 7)
		{
			error(lineNumber, "a vertex needs 3 coordinates (found " + std::to_string(numbers) + ")");
			return;
		}
		double xyz[3] = {0, 0, 0};
		for (int i = 1; i <= numbers; ++i)
		{
			double value = 0;
			const char* why = "";
			if (!parseCoordinate(m_tokens[i], value, why))
			{
				error(lineNumber, "vertex coordinate '" + printable(m_tokens[i]) + "' " + why);
				return;
			}
			if (i <= 3) xyz[i - 1] = value;
		}
		m_positions.push_back(btVector3(btScalar(xyz[0]), btScalar(xyz[1]), btScalar(xyz[2])));
	}

	// The vertex part of "v", "v/t", "v//n" or "v/t/n" as a 0-based index; -1 (with an error) if bad.
	int resolveIndex(std::string_view token, int lineNumber)
	{
		const std::size_t slash = token.find('/');
		const std::string_view vertexPart = token.substr(0, slash);
		long long index = 0;
		if (!parseInteger(vertexPart, index))
		{
			error(lineNumber, "face vertex '" + printable(token) + "' is not an index");
			return -1;
		}
		if (slash != std::string_view::npos)
		{
			// The texture and normal parts are not used, but a malformed one means a malformed line.
			std::string_view rest = token.substr(slash + 1);
			while (true)
			{
				const std::size_t next = rest.find('/');
				const std::string_view part = rest.substr(0, next);
				long long ignored = 0;
				if (!part.empty() && !parseInteger(part, ignored))
				{
					error(lineNumber, "face vertex '" + printable(token) + "' has a malformed texture or normal index");
					return -1;
				}
				if (next == std::string_view::npos) break;
				rest = rest.substr(next + 1);
			}
		}
		const long long count = m_positions.size();
		const long long resolved = index > 0 ? index - 1 : count + index;  // negative: relative to the last vertex
		if (index == 0 || resolved < 0 || resolved >= count)
		{
			error(lineNumber, "face vertex index " + std::string(vertexPart) + " is out of range (" +
			                      std::to_string(count) + " vertices defined so far)");
			return -1;
		}
		return int(resolved);
	}

	void parseFace(int lineNumber)
	{
		const int corners = int(m_tokens.size()) - 1;
		if (corners < 3)
		{
			error(lineNumber, "a face needs at least 3 vertices (found " + std::to_string(corners) + ")");
			return;
		}
		m_faceIndices.clear();
		m_facePoints.resize(0);
		for (int i = 1; i <= corners; ++i)
		{
			const int index = resolveIndex(m_tokens[i], lineNumber);
			if (index < 0) return;
			m_faceIndices.push_back(index);
			m_facePoints.push_back(m_positions[index]);
		}
		m_faceTriangles.resize(0);
		triangulatePolygon(&m_facePoints[0], corners, m_faceTriangles);
		GroupFaces& group = currentGroup();
		int dropped = 0;
		for (int t = 0; t < m_faceTriangles.size(); t += 3)
		{
			const int a = m_faceIndices[m_faceTriangles[t]], b = m_faceIndices[m_faceTriangles[t + 1]],
			          c = m_faceIndices[m_faceTriangles[t + 2]];
			if (a == b || b == c || c == a)
			{
				++dropped;  // a repeated vertex gives a triangle without area
				continue;
			}
			group.triangles.push_back(a);
			group.triangles.push_back(b);
			group.triangles.push_back(c);
		}
		if (dropped)
			warning(lineNumber,
			        "face repeats a vertex; " + std::to_string(dropped) + " degenerate triangle(s) dropped");
	}

	void selectGroup()
	{
		std::string name;
		for (std::size_t i = 1; i < m_tokens.size(); ++i)
		{
			if (!name.empty()) name += ' ';
			name += m_tokens[i];
		}
		m_currentName = name.empty() ? "default" : name;
		m_current = -1;  // looked up (or created) at the group's next face, so empty groups make no mesh
	}

	GroupFaces& currentGroup()
	{
		if (m_current < 0)
		{
			auto found = m_groupByName.find(m_currentName);
			if (found == m_groupByName.end())
			{
				m_current = int(m_groups.size());
				m_groups.push_back({m_currentName, {}});
				m_groupByName.emplace(m_currentName, m_current);
			}
			else
				m_current = found->second;
		}
		return m_groups[m_current];
	}

	void finish()
	{
		if (m_model.errors.empty())
		{
			std::size_t triangles = 0;
			for (const GroupFaces& group : m_groups) triangles += group.triangles.size();
			if (triangles == 0) error(0, "the input has no faces");
		}
		if (!m_model.errors.empty()) return;
		std::unordered_map<int, int> localIndex;
		for (const GroupFaces& group : m_groups)
		{
			if (group.triangles.empty()) continue;  // every face of the group was degenerate
			m_model.meshes.emplace_back();
			ObjMesh& mesh = m_model.meshes.back();
			mesh.name = group.name;
			localIndex.clear();
			mesh.indices.reserve(int(group.triangles.size()));
			for (int global : group.triangles)
			{
				auto inserted = localIndex.emplace(global, mesh.vertices.size());
				if (inserted.second) mesh.vertices.push_back(m_positions[global]);
				mesh.indices.push_back(inserted.first->second);
			}
		}
	}

	ObjModel& m_model;
	bool m_stopped = false;
	std::vector<std::string_view> m_tokens;
	btAlignedObjectArray<btVector3> m_positions;
	std::vector<int> m_faceIndices;
	btAlignedObjectArray<btVector3> m_facePoints;
	btAlignedObjectArray<int> m_faceTriangles;
	std::vector<GroupFaces> m_groups;
	std::unordered_map<std::string, int> m_groupByName;
	std::string m_currentName = "default";
	int m_current = -1;
};
}  // namespace

int ObjModel::numTriangles() const
{
	int total = 0;
	for (const ObjMesh& mesh : meshes) total += mesh.numTriangles();
	return total;
}

std::string ObjModel::describeErrors() const
{
	std::string out;
	for (const ObjMessage& message : errors) out += "line " + std::to_string(message.line) + ": " + message.text + "\n";
	return out;
}

bool loadObjFromMemory(const char* text, std::size_t size, ObjModel& model)
{
	model = ObjModel();
	if (!text && size != 0)
	{
		btAssert(!"loadObjFromMemory: null text with a non-zero size");
		model.errors.push_back({0, "null text with a non-zero size"});
		return false;
	}
	ObjParser parser(model);
	parser.parse(std::string_view(text ? text : "", text ? size : 0));
	return model.ok();
}

bool loadObjFile(const char* path, ObjModel& model)
{
	model = ObjModel();
	if (!path)
	{
		btAssert(!"loadObjFile: null path");
		model.errors.push_back({0, "null path"});
		return false;
	}
	std::FILE* file = std::fopen(path, "rb");
	if (!file)
	{
		model.errors.push_back({0, std::string("cannot open '") + path + "'"});
		return false;
	}
	std::string text;
	char buffer[65536];
	std::size_t got = 0;
	while ((got = std::fread(buffer, 1, sizeof(buffer), file)) > 0) text.append(buffer, got);
	const bool readError = std::ferror(file) != 0;
	std::fclose(file);
	if (readError)
	{
		model.errors.push_back({0, std::string("cannot read '") + path + "'"});
		return false;
	}
	return loadObjFromMemory(text.data(), text.size(), model);
}
}  // namespace caliber

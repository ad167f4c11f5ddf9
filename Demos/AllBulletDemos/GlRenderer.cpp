// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "GlRenderer.h"

#define GLFW_INCLUDE_GLCOREARB
#define GL_GLEXT_PROTOTYPES
#include <GLFW/glfw3.h>

#include <cmath>

namespace all_bullet_demos
{
namespace
{
// The lights follow the camera as in the software renderer (Demos/Common/Renderer.cpp): a key light
// from above, the camera's side and its left, a weak fill from the right.
const char* const kSolidVertex = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec3 color;
layout(location = 3) in float checker;
uniform mat4 viewProjection;
out vec3 worldPosition;
out vec3 worldNormal;
out vec3 baseColor;
out float checkered;
void main()
{
	worldPosition = position;
	worldNormal = normal;
	baseColor = color;
	checkered = checker;
	gl_Position = viewProjection * vec4(position, 1.0);
}
)";

const char* const kSolidFragment = R"(#version 330 core
in vec3 worldPosition;
in vec3 worldNormal;
in vec3 baseColor;
in float checkered;
uniform vec3 eye;
uniform vec3 keyLight;
uniform vec3 fillLight;
out vec4 fragment;
void main()
{
	vec3 n = normalize(worldNormal);
	vec3 toEye = normalize(eye - worldPosition);
	if (dot(n, toEye) < 0.0) n = -n;  // two-sided, as open meshes need
	vec3 base = baseColor;
	if (checkered > 0.5)
	{
		vec3 a = abs(n);
		vec2 uv = a.x > a.y && a.x > a.z ? worldPosition.yz : (a.y > a.z ? worldPosition.zx : worldPosition.xy);
		if (mod(floor(uv.x) + floor(uv.y), 2.0) != 0.0) base *= 0.88;
	}
	float key = max(dot(n, keyLight), 0.0);
	float fill = max(dot(n, fillLight), 0.0);
	float specular = pow(max(dot(n, normalize(keyLight + toEye)), 0.0), 32.0) * 0.15;
	fragment = vec4(base * (0.32 + 0.6 * key + 0.18 * fill) + vec3(specular), 1.0);
}
)";

const char* const kLineVertex = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 color;
uniform mat4 viewProjection;
out vec3 lineColor;
void main()
{
	lineColor = color;
	gl_Position = viewProjection * vec4(position, 1.0);
}
)";

const char* const kLineFragment = R"(#version 330 core
in vec3 lineColor;
out vec4 fragment;
void main() { fragment = vec4(lineColor, 1.0); }
)";

bool compile(GLenum type, const char* source, GLuint& shader, std::string& error)
{
	shader = glCreateShader(type);
	glShaderSource(shader, 1, &source, nullptr);
	glCompileShader(shader);
	GLint ok = 0;
	glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
	if (ok) return true;
	char log[2048];
	glGetShaderInfoLog(shader, sizeof(log), nullptr, log);
	error = std::string("shader compilation failed: ") + log;
	return false;
}

bool link(const char* vertex, const char* fragment, GLuint& program, std::string& error)
{
	GLuint vs = 0, fs = 0;
	if (!compile(GL_VERTEX_SHADER, vertex, vs, error) || !compile(GL_FRAGMENT_SHADER, fragment, fs, error))
		return false;
	program = glCreateProgram();
	glAttachShader(program, vs);
	glAttachShader(program, fs);
	glLinkProgram(program);
	glDeleteShader(vs);
	glDeleteShader(fs);
	GLint ok = 0;
	glGetProgramiv(program, GL_LINK_STATUS, &ok);
	if (ok) return true;
	char log[2048];
	glGetProgramInfoLog(program, sizeof(log), nullptr, log);
	error = std::string("shader link failed: ") + log;
	return false;
}

// Column-major 4x4 matrices, as OpenGL reads them.
struct Matrix
{
	float m[16];
};

Matrix multiply(const Matrix& a, const Matrix& b)
{
	Matrix r;
	for (int c = 0; c < 4; ++c)
		for (int row = 0; row < 4; ++row)
		{
			float sum = 0;
			for (int k = 0; k < 4; ++k) sum += a.m[k * 4 + row] * b.m[c * 4 + k];
			r.m[c * 4 + row] = sum;
		}
	return r;
}

void push(std::vector<float>& data, const btVector3& v)
{
	data.push_back(float(v.x()));
	data.push_back(float(v.y()));
	data.push_back(float(v.z()));
}
}  // namespace

bool GlRenderer::init(std::string& error)
{
	if (!link(kSolidVertex, kSolidFragment, m_solidProgram, error)) return false;
	if (!link(kLineVertex, kLineFragment, m_lineProgram, error)) return false;
	glGenVertexArrays(1, &m_solidVao);
	glGenBuffers(1, &m_solidVbo);
	glBindVertexArray(m_solidVao);
	glBindBuffer(GL_ARRAY_BUFFER, m_solidVbo);
	const GLsizei solidStride = 10 * sizeof(float);
	glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, solidStride, reinterpret_cast<void*>(0));
	glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, solidStride, reinterpret_cast<void*>(3 * sizeof(float)));
	glVertexAttribPointer(2, 3, GL_FLOAT, GL_FALSE, solidStride, reinterpret_cast<void*>(6 * sizeof(float)));
	glVertexAttribPointer(3, 1, GL_FLOAT, GL_FALSE, solidStride, reinterpret_cast<void*>(9 * sizeof(float)));
	for (int i = 0; i < 4; ++i) glEnableVertexAttribArray(GLuint(i));
	glGenVertexArrays(1, &m_lineVao);
	glGenBuffers(1, &m_lineVbo);
	glBindVertexArray(m_lineVao);
	glBindBuffer(GL_ARRAY_BUFFER, m_lineVbo);
	const GLsizei lineStride = 6 * sizeof(float);
	glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, lineStride, reinterpret_cast<void*>(0));
	glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, lineStride, reinterpret_cast<void*>(3 * sizeof(float)));
	glEnableVertexAttribArray(0);
	glEnableVertexAttribArray(1);
	glBindVertexArray(0);
	return true;
}

void GlRenderer::shutdown()
{
	glDeleteBuffers(1, &m_solidVbo);
	glDeleteBuffers(1, &m_lineVbo);
	glDeleteVertexArrays(1, &m_solidVao);
	glDeleteVertexArrays(1, &m_lineVao);
	glDeleteProgram(m_solidProgram);
	glDeleteProgram(m_lineProgram);
	m_solidProgram = m_lineProgram = m_solidVao = m_solidVbo = m_lineVao = m_lineVbo = 0;
}

void GlRenderer::draw(const caliber::demo::Scene& scene, const caliber::demo::Camera& camera, int width, int height,
                      bool wireframe)
{
	const caliber::demo::RenderOptions defaults;
	glViewport(0, 0, width, height);
	glClearColor(float(defaults.background.x()), float(defaults.background.y()), float(defaults.background.z()), 1);
	glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
	if (width < 1 || height < 1) return;

	// The camera's basis, as the software renderer builds it.
	const btVector3 forward = (camera.target - camera.eye).normalized();
	btVector3 right = forward.cross(camera.up);
	if (right.length2() < btScalar(1e-12)) right = forward.cross(btVector3(1, 0, 0));
	right.normalize();
	const btVector3 up = right.cross(forward);
	const double distance = double((camera.target - camera.eye).length());
	const float nearPlane = float(std::max(1e-3, 0.01 * distance)), farPlane = float(distance * 100 + 1000);
	const float f = float(1 / std::tan(double(camera.fieldOfViewDegrees) * M_PI / 360.0));
	const float aspect = float(width) / float(height);
	Matrix view = {{float(right.x()), float(up.x()), float(-forward.x()), 0, float(right.y()), float(up.y()),
	                float(-forward.y()), 0, float(right.z()), float(up.z()), float(-forward.z()), 0,
	                float(-right.dot(camera.eye)), float(-up.dot(camera.eye)), float(forward.dot(camera.eye)), 1}};
	Matrix projection = {{f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (farPlane + nearPlane) / (nearPlane - farPlane), -1, 0,
	                      0, 2 * farPlane * nearPlane / (nearPlane - farPlane), 0}};
	const Matrix viewProjection = multiply(projection, view);
	const btVector3 key = (btVector3(0, 1, 0) - forward * btScalar(0.6) - right * btScalar(0.4)).normalized();
	const btVector3 fill =
	    (right * btScalar(0.8) - forward * btScalar(0.3) + btVector3(0, btScalar(0.2), 0)).normalized();

	m_solidData.clear();
	for (const caliber::demo::SceneTriangle& t : scene.triangles())
		for (int k = 0; k < 3; ++k)
		{
			push(m_solidData, t.corner[k]);
			push(m_solidData, t.normal[k]);
			push(m_solidData, t.color);
			m_solidData.push_back(t.checker ? 1.0f : 0.0f);
		}
	m_lineData.clear();
	for (const caliber::demo::SceneLine& l : scene.lines())
	{
		push(m_lineData, l.from);
		push(m_lineData, l.color);
		push(m_lineData, l.to);
		push(m_lineData, l.color);
	}
	m_pointData.clear();
	for (const caliber::demo::ScenePoint& p : scene.points())
	{
		push(m_pointData, p.position);
		push(m_pointData, p.color);
	}

	glEnable(GL_DEPTH_TEST);
	glPolygonMode(GL_FRONT_AND_BACK, wireframe ? GL_LINE : GL_FILL);
	glUseProgram(m_solidProgram);
	glUniformMatrix4fv(glGetUniformLocation(m_solidProgram, "viewProjection"), 1, GL_FALSE, viewProjection.m);
	glUniform3f(glGetUniformLocation(m_solidProgram, "eye"), float(camera.eye.x()), float(camera.eye.y()),
	            float(camera.eye.z()));
	glUniform3f(glGetUniformLocation(m_solidProgram, "keyLight"), float(key.x()), float(key.y()), float(key.z()));
	glUniform3f(glGetUniformLocation(m_solidProgram, "fillLight"), float(fill.x()), float(fill.y()), float(fill.z()));
	glBindVertexArray(m_solidVao);
	glBindBuffer(GL_ARRAY_BUFFER, m_solidVbo);
	glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(m_solidData.size() * sizeof(float)), m_solidData.data(), GL_STREAM_DRAW);
	glDrawArrays(GL_TRIANGLES, 0, GLsizei(m_solidData.size() / 10));
	glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);

	// Lines and points over the solids (joint frames inside bodies stay visible).
	glDisable(GL_DEPTH_TEST);
	glUseProgram(m_lineProgram);
	glUniformMatrix4fv(glGetUniformLocation(m_lineProgram, "viewProjection"), 1, GL_FALSE, viewProjection.m);
	glBindVertexArray(m_lineVao);
	glBindBuffer(GL_ARRAY_BUFFER, m_lineVbo);
	glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(m_lineData.size() * sizeof(float)), m_lineData.data(), GL_STREAM_DRAW);
	glDrawArrays(GL_LINES, 0, GLsizei(m_lineData.size() / 6));
	glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(m_pointData.size() * sizeof(float)), m_pointData.data(), GL_STREAM_DRAW);
	glPointSize(5);
	glDrawArrays(GL_POINTS, 0, GLsizei(m_pointData.size() / 6));
	glBindVertexArray(0);
	glEnable(GL_DEPTH_TEST);
}
void GlRenderer::drawText(const std::vector<caliber::demo::TextCell>& cells, const btVector3& color, int width,
                          int height)
{
	if (width < 1 || height < 1 || cells.empty()) return;
	m_textData.clear();
	const btVector3 shadow(btScalar(0.97), btScalar(0.97), btScalar(0.97));
	for (int pass = 0; pass < 2; ++pass)
	{
		const btVector3& c = pass == 0 ? shadow : color;
		const float offset = pass == 0 ? 1.0f : 0.0f;
		for (const caliber::demo::TextCell& cell : cells)
		{
			const float x0 = cell.x + offset, y0 = cell.y + offset, x1 = x0 + cell.size, y1 = y0 + cell.size;
			const float corners[6][2] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y0}, {x1, y1}, {x0, y1}};
			for (const auto& corner : corners)
			{
				push(m_textData, btVector3(btScalar(corner[0]), btScalar(corner[1]), 0));
				push(m_textData, c);
			}
		}
	}
	// Window pixels (y down) to clip space.
	const Matrix pixels = {{2.0f / float(width), 0, 0, 0, 0, -2.0f / float(height), 0, 0, 0, 0, 1, 0, -1, 1, 0, 1}};
	glDisable(GL_DEPTH_TEST);
	glUseProgram(m_lineProgram);
	glUniformMatrix4fv(glGetUniformLocation(m_lineProgram, "viewProjection"), 1, GL_FALSE, pixels.m);
	glBindVertexArray(m_lineVao);
	glBindBuffer(GL_ARRAY_BUFFER, m_lineVbo);
	glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(m_textData.size() * sizeof(float)), m_textData.data(), GL_STREAM_DRAW);
	glDrawArrays(GL_TRIANGLES, 0, GLsizei(m_textData.size() / 6));
	glBindVertexArray(0);
	glEnable(GL_DEPTH_TEST);
}
}  // namespace all_bullet_demos

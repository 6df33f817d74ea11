#version 450 core
// World-space vertices (animation is applied on the CPU) to clip space.

layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec2 uv;

uniform mat4 clipFromWorld;

layout(location = 0) out vec3 worldPosition;
layout(location = 1) out vec3 worldNormal;
layout(location = 2) out vec2 textureUv;

void main() {
  worldPosition = position;
  worldNormal = normal;
  textureUv = uv;
  gl_Position = clipFromWorld * vec4(position, 1.0);
}

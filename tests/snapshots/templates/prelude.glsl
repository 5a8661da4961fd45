// Snapshot copy of templates/prelude.glsl. Covers: the prelude (PI, CrtFrag) every stage snippet sees.
// Shared by every stage snippet.
//
// One coordinate convention on every target: uv (0,0) is the top-left of the source image and of
// the output; pixel coordinates have their origin at the output's top-left corner with pixel
// centres at +0.5 (what gl_FragCoord gives on Vulkan and FRAGCOORD in Godot). They are derived
// from vTexCoord * outputSize rather than gl_FragCoord, whose origin differs between APIs.
const float PI = 3.14159265358979;

struct CrtFrag {
    vec2 screenUv;  // unwarped output position, 0..1
    vec2 pixel;     // output pixel coordinate: screenUv * outputSize
    vec2 uv;        // texture coordinate after the warp stages
    vec2 centered;  // uv * 2 - 1, after the warp stages
};

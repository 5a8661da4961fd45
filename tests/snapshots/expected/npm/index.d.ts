// Types of crtforge-presets: the manifest an export writes (manifestVersion 2, WGSL entries) and
// the API of crt-webgpu.mjs and index.mjs. WebGPU types come from @webgpu/types (or lib.dom).
/// <reference types="@webgpu/types" />

export type ParamValue = number | [number, number, number];

/** One member of a pass's std140 uniform block: a builtin (outputSize, time, ...) or a runtime param. */
export interface UniformMember {
  name: string;
  type: 'float' | 'int' | 'uint' | 'bool' | 'vec2' | 'vec3' | 'vec4' | 'ivec2' | 'color' | string;
  offset: number;
  size: number;
  builtin?: boolean;
  stage?: string;
  range?: [number, number];
  step?: number;
  default?: ParamValue;
  unit?: string;
  doc?: string;
  values?: string[];
  role?: string;
  reduceBy?: number;
}

export interface UniformBlock {
  name: string;
  instance: string;
  layout: 'std140';
  set: number;
  binding: number;
  size: number;
  allocationSize: number;
  members: UniformMember[];
}

/** A texture a pass reads: `from` is original, original@N, a pass alias, alias@previous or lut:NAME. */
export interface PassTexture {
  name: string;
  set: number;
  binding: number;
  from: string;
  filter: 'nearest' | 'linear';
  wrap: 'clamp_to_edge' | 'repeat' | 'mirrored_repeat' | 'clamp_to_border';
  mipmap: boolean;
  /** With mipmap: how the levels blend ('linear': the two nearest weighed; 'nearest': the nearest level). */
  mipFilter?: 'linear' | 'nearest';
}

export interface BindGroupLayoutEntryJson {
  binding: number;
  name: string;
  visibility: Array<'vertex' | 'fragment' | 'compute'>;
  buffer?: { type: 'uniform'; minBindingSize: number };
  texture?: { sampleType: GPUTextureSampleType; viewDimension: GPUTextureViewDimension; multisampled: boolean };
  sampler?: { type: GPUSamplerBindingType };
  pairedSampler?: string;
  pairedTexture?: string;
}

export interface WgslTarget {
  /** Path of the pass's WGSL module, relative to the package (or the export) root. */
  shader: string;
  bindings: Record<string, string>;
  entryPoints: { vertex: string; fragment: string };
  bindGroupLayout: { group: number; entries: BindGroupLayoutEntryJson[] };
  uniformBuffer?: {
    struct: string;
    binding: number;
    size: number;
    note: string;
    members: Array<{ name: string; type: string; offset: number; size: number }>;
  };
}

export interface PassScale {
  type: 'source' | 'viewport' | 'absolute';
  factor?: number;
  pixels?: number;
}

export interface ManifestPass {
  alias: string;
  scale?: { x: PassScale; y: PassScale };
  format?: 'rgba8' | 'srgba8' | 'rgba16f' | 'rgba32f' | string;
  frameCountMod?: number;
  /** What feeds the pass's main input, read by its shader or not ("original", a pass alias, ...). */
  input?: string;
  stages: Array<{ stage: string; form: string }>;
  baked: Record<string, ParamValue | string | boolean>;
  uniformBlock?: UniformBlock;
  textures: PassTexture[];
  targets: { wgsl: WgslTarget } & Record<string, unknown>;
}

export interface ManifestLut {
  /** Path of the LUT's PNG (any PNG: crtforge's are 8-bit RGBA, an imported preset's as the library has them), relative to the package root. */
  file: string;
  filter: 'nearest' | 'linear';
  wrap: string;
  generator?: string;
  layout?: string;
  params?: Record<string, number>;
}

export interface ManifestScene {
  source?: { pixelAspect?: [number, number]; fit?: string; size?: [number, number] };
  display?: { fit?: 'stretch' | 'aspect' | 'integer'; aspect?: [number, number] };
  fps?: number;
  historyFrames?: number;
  feedback?: boolean;
}

export interface ManifestPreset {
  doc: string;
  lineage: string[];
  precision: 'high' | 'medium';
  uniforms: string;
  scene?: ManifestScene;
  luts?: Record<string, ManifestLut>;
  vertexInput: string;
  passes: ManifestPass[];
}

export interface Manifest {
  generator: string;
  manifestVersion: 2;
  options: { uniforms: string; precision: string };
  targets: string[];
  presets: Record<string, ManifestPreset>;
}

/** A param as the module reports it: the manifest's description plus its current value. */
export interface CrtParam {
  name: string;
  type: string;
  range?: [number, number];
  step?: number;
  default: ParamValue;
  unit?: string;
  doc?: string;
  value: ParamValue;
}

export interface CompilationMessage {
  type: 'error' | 'warning' | 'info';
  lineNum: number;
  linePos: number;
  message: string;
}

export interface Rect { x: number; y: number; width: number; height: number }

export interface CrtPass {
  readonly alias: string;
  readonly textures: string[];
  params(): CrtParam[];
  hasParam(name: string): boolean;
  setParam(name: string, value: ParamValue): void;
  encode(encoder: GPUCommandEncoder, options: {
    source: GPUTexture;
    textures?: Record<string, GPUTexture>;
    target: GPUTextureView;
    width: number;
    height: number;
    viewport?: Rect | null;
    time?: number;
    frameCount?: number;
    /** The screen's [width, height] a scene's last pass draws (default: [width, height]). */
    viewportSize?: [number, number];
  }): void;
  compilationInfo(): Promise<CompilationMessage[]>;
  destroy(): void;
}

export interface CrtScene {
  readonly passes: CrtPass[];
  params(): Array<CrtParam & { pass: string }>;
  setParam(name: string, value: ParamValue): void;
  screenRect(width: number, height: number, source: { width: number; height: number }, fit?: 'stretch' | 'aspect' | 'integer'): Rect;
  /** Records one frame; submit once per frame (uniforms are written with queue.writeBuffer). */
  encode(encoder: GPUCommandEncoder, options: {
    source: GPUTexture;
    target: GPUTextureView;
    width: number;
    height: number;
    frame?: number;
    time?: number;
    fit?: 'stretch' | 'aspect' | 'integer';
  }): void;
  destroy(): void;
}

export function createCrtPass(device: GPUDevice, options: { wgsl: string; preset: ManifestPass; format: GPUTextureFormat }): CrtPass;
export function createCrtScene(device: GPUDevice, options: {
  preset: ManifestPreset;
  wgsl: Record<string, string>;
  luts?: Record<string, GPUTexture>;
  format: GPUTextureFormat;
}): CrtScene;
export function screenRect(scene: ManifestScene, display: { width: number; height: number },
                           source: { width: number; height: number }, fit?: 'stretch' | 'aspect' | 'integer'): Rect;
export function passSizes(passes: ManifestPass[], source: { width: number; height: number },
                          screen: { width: number; height: number }): Array<{ width: number; height: number }>;
export function decodePng(bytes: Uint8Array | ArrayBuffer, name?: string): Promise<{ width: number; height: number; data: Uint8Array }>;
/** A LUT's PNG as an rgba8unorm texture; `mipmap`: with its mip chain (each level a linear blit of the one above). */
export function createLutTexture(device: GPUDevice, bytes: Uint8Array | ArrayBuffer, name?: string,
                                 options?: { mipmap?: boolean }): Promise<GPUTexture>;
/** The names of the LUTs a preset reads through a mip chain (create them with `mipmap: true`). */
export function mipmappedLuts(preset: ManifestPreset): Set<string>;
/** floor(log2(max(width, height))) + 1. */
export function mipLevelCount(width: number, height: number): number;
/** Records levels 1.. of `texture` (RENDER_ATTACHMENT usage) from its level 0, as RetroArch fills a mip chain. */
export function encodeMipmaps(device: GPUDevice, encoder: GPUCommandEncoder, texture: GPUTexture): void;

/** The package's manifest (read once). */
export function loadManifest(): Promise<Manifest>;
/** The names of the presets in the package. */
export function presetNames(): Promise<string[]>;
/** A whole preset, its WGSL and LUTs read from the package: ready to encode(). */
export function loadCrtPreset(device: GPUDevice, name: string, options: { format: GPUTextureFormat }): Promise<CrtScene>;

/**
 * The pass the framework adapters (crtforge-presets/three, /pixi, /babylon) return: one preset on a
 * framework's own GPUDevice, drawing between two of its textures (`Texture`: how that framework
 * names one).
 */
export interface FrameworkCrtPass<Texture> {
  readonly scene: CrtScene;
  params(): Array<CrtParam & { pass: string }>;
  setParam(name: string, value: ParamValue): void;
  /** Draws `input` through the preset into `output`, at output's size; submits on the framework's device. */
  render(input: Texture, output: Texture,
         options?: { frame?: number; time?: number; fit?: 'stretch' | 'aspect' | 'integer' }): Promise<void>;
  /** Records the pass into your encoder, onto a view of the format the pass was made for. */
  encode(encoder: GPUCommandEncoder, options: Parameters<CrtScene['encode']>[1]): void;
  /** The GPUTexture the framework made for a texture. */
  textureOf(texture: Texture): GPUTexture;
  destroy(): void;
}

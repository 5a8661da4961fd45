// Types of crtforge-presets/three. three.js itself is not a dependency: the pass uses the
// renderer's WebGPU backend through the members below.
/// <reference types="@webgpu/types" />
import type { CrtParam, CrtScene, ParamValue } from './index.js';

/** What the pass uses of a three.js WebGPURenderer (after `await renderer.init()`). */
export interface ThreeWebGPURendererLike {
  backend: { device: GPUDevice; get(object: object): { texture?: GPUTexture } | undefined };
  getRenderTarget(): unknown;
  setRenderTarget(renderTarget: unknown): void;
  clear(): void;
}

/** A three.js RenderTarget. */
export interface RenderTargetLike {
  texture: object;
}

export interface ThreeCrtPass {
  readonly scene: CrtScene;
  params(): Array<CrtParam & { pass: string }>;
  setParam(name: string, value: ParamValue): void;
  /** Draws `input` through the preset into `output`, at output's size; submits on the renderer's device. */
  render(input: RenderTargetLike, output: RenderTargetLike,
         options?: { frame?: number; time?: number; fit?: 'stretch' | 'aspect' | 'integer' }): Promise<void>;
  /** Records the pass into your encoder, onto a view of the format the pass was made for. */
  encode(encoder: GPUCommandEncoder, options: Parameters<CrtScene['encode']>[1]): void;
  /** The GPUTexture three made for a RenderTarget. */
  textureOf(renderTarget: RenderTargetLike): GPUTexture;
  destroy(): void;
}

export function createThreeCrtPass(renderer: ThreeWebGPURendererLike, name: string,
                                   options?: { format?: GPUTextureFormat }): Promise<ThreeCrtPass>;

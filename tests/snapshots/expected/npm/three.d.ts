// Types of crtforge-presets/three. three.js itself is not a dependency: the pass uses the
// renderer's WebGPU backend through the members below.
/// <reference types="@webgpu/types" />
import type { FrameworkCrtPass } from './index.js';

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

export type ThreeCrtPass = FrameworkCrtPass<RenderTargetLike>;

export function createThreeCrtPass(renderer: ThreeWebGPURendererLike, name: string,
                                   options?: { format?: GPUTextureFormat }): Promise<ThreeCrtPass>;

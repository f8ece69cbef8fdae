/**
 * JSON shapes that the IDE server sends and the browser client (src/api.ts) reads: one definition
 * for both sides. Types only — the browser imports this file, so it must not import Node modules.
 */

/** One entry of the workspace tree (GET /api/tree, /api/snapshot). */
export interface TreeEntry {
  name: string;
  /** Workspace-relative path with '/' separators. */
  path: string;
  type: 'file' | 'dir';
  children?: TreeEntry[];
}

/** What Generate All did: the report of codegen's generateArchitecture (Seam 4), paths relative to src-gen. */
export interface GenerateReport {
  created: string[];
  updated: string[];
  unchanged: string[];
  orphaned: string[];
  errors: unknown[];
  warnings: unknown[];
}

/** The answer of POST /api/generate: the report, the workspace-relative src-gen folder and the time taken. */
export interface GenerateResponse extends GenerateReport {
  srcGen: string;
  ms: number;
}

/** The answer of PUT /api/file. */
export interface FileWriteResponse {
  path: string;
  mtimeMs: number;
  /**
   * Set when the file is generated and its generated code (outside the protected regions) differed
   * from the file on disk: the server kept the disk's code, wrote the incoming regions into it, and
   * `content` is the text now on disk — the client reloads the tab from it.
   */
  merged?: true;
  reason?: string;
  content?: string;
}

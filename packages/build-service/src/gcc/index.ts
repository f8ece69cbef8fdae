/**
 * `@contract-studio/build-service/gcc`: gcc's diagnostics read from untrusted compiler output (the
 * text-format reader a build job falls back to) and ld's errors of a failed link, the diagnostic type and its one-line rendering,
 * and the protected-region lookup by line, without the rest of the build service (no Docker
 * client, no pipeline). The simulator reads the errors of its own compile with them (packages/
 * simulator harness/compile-diagnostics.ts), so that `contract simulate` names the user's file,
 * line and region as `contract build` does.
 */
export { movedToRegion, renderDiagnostic, type DiagnosticContext, type GccDiagnostic } from '../pipeline/gcc-diagnostics.js';
export { cutText, parseGccTextLine } from '../pipeline/gcc-text.js';
export { LinkErrorReader, parseLinkerLine, type LinkerLine } from '../pipeline/ld-text.js';
export { findProtectedRegions, regionAt, type ProtectedRegion } from '../pipeline/protected-regions.js';

export { START_MARKER, END_MARKER, END, startMarker, region, normaliseRegionId } from './markers.js';
export { RegionSyntaxError } from './region-error.js';
export { parseRegions, type Region, type ParsedFile } from './parse-regions.js';
export { mergeRegions, userRegions, type MergeResult, type DefaultContentCheck, type KnownDefaultCheck } from './merge-regions.js';
export { carryRenamedRegions, type CarriedRegion, type GeneratedOutput } from './carry-renamed-regions.js';

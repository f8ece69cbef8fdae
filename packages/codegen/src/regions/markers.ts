/**
 * The protected-region markers of report section 5 / docs/codegen.md "Protected regions": owned by
 * @contract-studio/conventions, which the IDE and the build service read them with too.
 */
export { START_MARKER, END_MARKER, END, startMarker, region, normaliseRegionId } from '@contract-studio/conventions';

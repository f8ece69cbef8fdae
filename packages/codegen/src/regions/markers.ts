/**
 * The protected-region markers of report section 5 / docs/codegen.md "Protected regions":
 *   /*PROTECTED REGION ID(<id>) ENABLED START*\/ ... /*PROTECTED REGION END*\/
 * The start marker may lack `ENABLED` (the user asks for the default to be regenerated).
 */

/**
 * Matches a start marker; group 1 = the ID, group 2 = `ENABLED` when present. Tolerates extra
 * blanks and line breaks between the words (code pasted from the report's PDF has them).
 */
export const START_MARKER = /\/\*\s*PROTECTED\s+REGION\s+ID\s*\(([^()\r\n]*)\)\s*(ENABLED\s+)?START\s*\*\//g;
/** Matches an end marker. */
export const END_MARKER = /\/\*\s*PROTECTED\s+REGION\s+END\s*\*\//g;

/** The start marker the generators write (always ENABLED: a fresh region keeps what the user types). */
export function startMarker(id: string): string {
    return `/*PROTECTED REGION ID(${id}) ENABLED START*/`;
}

export const END = '/*PROTECTED REGION END*/';

/** Wraps `content` in a region, the way generators write one. */
export function region(id: string, content: string): string {
    return `${startMarker(id)}${content}${END}`;
}

/**
 * The report spells some IDs `additionnal`; the generators write `additional`. Both spellings
 * designate the same region when reading existing files.
 */
export function normaliseRegionId(id: string): string {
    return id.trim().replace(/additionnal/g, 'additional');
}

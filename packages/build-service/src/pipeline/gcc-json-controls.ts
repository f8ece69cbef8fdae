/**
 * gcc's `-fdiagnostics-format=json` writes a message's bytes as they are: a control character in a
 * `#warning` (a BEL, an ESC, a tab) is written raw inside the JSON string, and a raw control
 * character makes the whole line invalid JSON (gcc 12 nests every diagnostic of a compilation after
 * a `#warning` in its `children`: one such byte hid the compilation's real errors, and gcc's own
 * -Wbidi-chars warning). The line is read anyway: each raw control character (U+0000–U+001F) inside
 * a string is written as its JSON escape, `\u0007`, and the line parsed again. One linear pass, no
 * regular expression; outside strings nothing is changed (JSON allows no such character there but
 * its whitespace, which stays whitespace).
 */

/** `text` parsed as JSON, read again with its strings' raw control characters escaped when it is not JSON as it is; undefined when it is no JSON either way. */
export function parseGccJson(text: string): unknown {
  try {
    return JSON.parse(text);
  } catch {
    /* gcc's raw control characters, perhaps: below */
  }
  const escaped = controlsEscapedInStrings(text);
  if (escaped === text) return undefined;
  try {
    return JSON.parse(escaped);
  } catch {
    return undefined;
  }
}

/** `text` with every raw control character inside a JSON string written `\u00XX` (the same text when there is none). */
export function controlsEscapedInStrings(text: string): string {
  let out = '';
  let from = 0;
  let inString = false;
  for (let i = 0; i < text.length; i++) {
    const c = text.charCodeAt(i);
    if (!inString) {
      if (c === 0x22) inString = true;
      continue;
    }
    if (c === 0x5c) i++; // backslash: the next character is escaped (an escaped control character stays invalid: not gcc's)
    else if (c === 0x22) inString = false;
    else if (c < 0x20) {
      out += `${text.slice(from, i)}\\u${c.toString(16).padStart(4, '0')}`;
      from = i + 1;
    }
  }
  return from === 0 ? text : out + text.slice(from);
}

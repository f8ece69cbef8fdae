/**
 * Files are handled as "byte strings" (one char per byte, latin1) so that user code in any
 * encoding is kept byte for byte; generated text (JS strings) is converted through UTF-8.
 */
export function toByteString(text: string): string {
    return Buffer.from(text, 'utf8').toString('latin1');
}

export function bytesOf(byteString: string): Buffer {
    return Buffer.from(byteString, 'latin1');
}

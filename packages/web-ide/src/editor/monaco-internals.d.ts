/**
 * The two pieces of Monaco's internals the IDE reaches (word-suggestions.ts), which the package
 * ships without types: its service registry and the configuration service it holds.
 */
declare module 'monaco-editor/editor/standalone/browser/standaloneServices.js' {
  export const StandaloneServices: { get<T>(id: { readonly __brand?: T } & object): T };
}
declare module 'monaco-editor/platform/configuration/common/configuration.js' {
  export interface ConfigurationService {
    /** `key` may be a language override, `[languageId]`, whose value holds `editor.*` settings. */
    updateValue(key: string, value: unknown): Promise<void>;
  }
  export const IConfigurationService: { readonly __brand?: ConfigurationService };
}

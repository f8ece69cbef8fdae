/** "New project" templates: one place for the IDE and `contract new`, in the language package. */
export { PROJECT_TEMPLATES } from '@contract-studio/language';

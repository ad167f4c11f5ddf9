// Placeholder translation unit for a layer whose sources land in a later step.

// mixtrace command line entry point (placeholder until the render command lands).
int main() { return 0; }

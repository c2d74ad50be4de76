// placeholder main: replaced by the covcontact command
int main() { return 0; }

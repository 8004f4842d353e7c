from fnet.cli import main

raise SystemExit(main())
